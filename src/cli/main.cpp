// shadowlab: render scenes with published real-time shadow algorithms and export their internals.
// Run `shadowlab --help` or `shadowlab <command> --help`.
#include "cli/Commands.h"
#include "core/Error.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv)
{
  CLI::App app{ "ShadowLab: real-time shadow algorithms, rendered and opened up.\n"
                "Every technique writes its image, visibility and internal buffers (VTK image data for ParaView)." };
  app.require_subcommand(1);

  sl::RenderOptions render;
  CLI::App* renderCommand = app.add_subcommand("render", "Render a scene with one technique into an output directory");
  renderCommand->add_option("scene", render.sceneFile, "Scene file (JSON, see README 'Scene format')")->required();
  renderCommand->add_option("--technique,-t", render.technique, "Technique name (see `shadowlab list`)")
    ->capture_default_str();
  renderCommand->add_option("--set,-s", render.settings, "Technique parameter, key=value (repeatable)");
  renderCommand->add_option("--resolution,-r", render.resolution, "Image size WxH (default: the scene camera's)");
  renderCommand->add_option("--out,-o", render.outDir, "Output directory (replaced atomically)")->capture_default_str();
  renderCommand->add_option("--light", render.lightIndex, "Index of the scene light that casts shadows")
    ->capture_default_str();
  renderCommand->add_flag("--quiet,-q", render.quiet, "Print nothing on success");

  bool listJson = false;
  CLI::App* listCommand = app.add_subcommand("list", "List techniques with their parameters, defaults and ranges");
  listCommand->add_flag("--json", listJson, "Machine-readable output");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& error)
  {
    return app.exit(error);
  }

  try
  {
    if (renderCommand->parsed())
    {
      return sl::runRender(render, std::cerr);
    }
    if (listCommand->parsed())
    {
      return sl::runList(listJson, std::cout);
    }
  }
  catch (const sl::InputError& error)
  {
    std::cerr << "shadowlab: error: " << error.what() << "\n";
    return 1;
  }
  catch (const sl::GraphicsError& error)
  {
    std::cerr << "shadowlab: graphics error: " << error.what() << "\n";
    return 2;
  }
  catch (const std::exception& error)
  {
    std::cerr << "shadowlab: internal error: " << error.what() << "\n";
    return 3;
  }
  return 0;
}
