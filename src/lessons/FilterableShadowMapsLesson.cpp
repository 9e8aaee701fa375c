// Lesson: light bleeding, ringing and moments. The filterable shadow maps (survey §6: VSM, layered VSM, convolution
// shadow maps; Peters & Klein 2015: moment shadow maps) each replace the shadow test by something linear in a stored
// quantity, so that the map can be blurred before the test; each pays for it with its own error. light_leak (the
// method's visibility minus PCF over the same texels) puts the four on one scale.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

#include <string>
#include <tuple>
#include <vector>

namespace sl
{

namespace
{
// A box wide enough that the overlap halo of stacked-occluders spans several pixels of the page's figures, on a map
// small enough that the five methods render in seconds on llvmpipe (tests/cli/LessonClaimsTest.cpp asserts it). At
// contact a narrower one: PCF, the truth, compares one receiver depth over the box, and over 11 texels of contact's
// sloped light it shadows the lit ground itself (acne), which would pass for every method's error.
constexpr int filterableBoxTexels = 11;
constexpr int filterableContactBoxTexels = 5;
constexpr int filterableMapTexels = 512;
} // namespace

Lesson filterableShadowMapsLesson()
{
  Lesson lesson{ "filterable-shadow-maps", "Light bleeding, ringing and moments: VSM, layered VSM, CSM and MSM",
    "Four ways to make a shadow map filterable: where does each one's approximation let light in, and which leaks "
    "least on the same texels?" };
  lesson.build = [](LessonBuilder& lesson) {
    const std::string box = std::to_string(filterableBoxTexels);
    const std::string contactBox = std::to_string(filterableContactBoxTexels);
    const std::string map = "shadow_map_size=" + std::to_string(filterableMapTexels);
    lesson.sceneNote(
      "A shadow map cannot be blurred: the shadow test is a step in the stored depth, and the average of steps is "
      "not the step of the average. The filterable methods store something the test is linear in, blur that, and "
      "reconstruct the test from it (survey §6). **VSM** stores depth and squared depth and bounds the test by "
      "Chebyshev's inequality; the bound bleeds light where the box holds occluders at different depths. **Layered "
      "VSM** (LM08) splits the depth range into layers, each a VSM of the depths clamped into it, so occluders of an "
      "earlier layer add no variance to a later one. **Convolution shadow maps** (CSM, Annen et al. 2007) expand the "
      "step in a truncated Fourier series of M terms whose sine and cosine images are blurred; the truncated step "
      "never reaches 0 (an umbra reads the series at its widest depth gap) and is smeared over about 1/M of the "
      "depth range, which lets light in at contact. **Moment shadow maps** "
      "(MSM, Peters & Klein 2015) store four power moments and take the sharpest distribution with those moments "
      "(Hamburger 4MSM), a bound far tighter than Chebyshev's. `light_leak` is each method's visibility minus PCF over "
      "the same box of texels of the same " + std::to_string(filterableMapTexels) +
      "-texel map (red = light let in, blue = too dark): on `stacked-occluders` (squares at heights 0.6 and 1.5, a "
      "box of " + box + " texels) where VSM bleeds, and on `contact` (a box standing on the ground, " + contactBox +
      " texels) where CSM's smeared step shows. No light bleeding reduction, so each method's own error is what is "
      "drawn.");
    const std::vector<std::tuple<std::string, std::string, std::string>> scenes = { { "", "stacked-occluders", box },
      { "-contact", "contact", contactBox } };
    for (const auto& [suffix, dataset, sceneBox] : scenes)
    {
      const std::string pcf = "pcf" + suffix;
      const std::string prefilter = "prefilter_texels=" + sceneBox;
      lesson.render({ pcf, dataset, "pcf", { map, "kernel_texels=" + sceneBox }, {}, "" });
      lesson.render({ "vsm" + suffix, dataset, "vsm", { map, prefilter, "light_bleeding_reduction=0" }, {}, pcf });
      lesson.render({ "lvsm" + suffix, dataset, "lvsm", { map, prefilter, "light_bleeding_reduction=0" }, {}, pcf });
      lesson.render({ "csm-4" + suffix, dataset, "convsm", { map, prefilter, "terms=4" }, {}, pcf });
      lesson.render({ "csm-16" + suffix, dataset, "convsm", { map, prefilter, "terms=16" }, {}, pcf });
      lesson.render({ "msm" + suffix, dataset, "msm", { map, prefilter }, {}, pcf });
    }
    const std::vector<std::string> methods = { "vsm", "lvsm", "csm-4", "csm-16", "msm" };
    std::vector<std::string> contactMethods;
    for (const std::string& method : methods)
    {
      contactMethods.push_back(method + "-contact");
    }

    lesson.montage("light_leak", "**light_leak on one scale**, stacked-occluders (VSM, layered VSM, CSM with 4 and 16 "
      "terms, MSM): VSM's halo where the upper occluder's shadow overlaps the lower one's; what is left of it in the "
      "others.", methods, "light_leak");
    lesson.montage("light_leak_contact", "**light_leak on one scale at contact** (the `contact` box on the ground), the "
      "same five methods.", contactMethods, "light_leak");
    lesson.errorMontage("error", "**Visibility against PCF over the same box**, stacked-occluders (red = too bright, "
      "blue = too dark).", methods);
    lesson.probe("probe", "**Where VSM bleeds most, inside:** its box's moments, Chebyshev's bound and the true "
      "filtered test over the same texels.", "vsm", LessonPixel::largestValue("light_leak"));

    for (const std::string& method : methods)
    {
      lesson.measure("largest light_leak", method, "/buffers/light_leak/max");
      lesson.measure("mean light_leak", method, "/buffers/light_leak/mean");
      lesson.measure("share of pixels off PCF by more than 0.05", method, "/error/covered/fraction_above_0.05");
      lesson.measure("RMSE against PCF", method, "/error/covered/rmse");
    }
    for (const std::string& method : contactMethods)
    {
      lesson.measure("largest light_leak", method, "/buffers/light_leak/max");
      lesson.measure("smallest light_leak", method, "/buffers/light_leak/min");
      lesson.measure("RMSE against PCF", method, "/error/covered/rmse");
    }

    const double vsmLeak = lesson.value("vsm", "/buffers/light_leak/max");
    lesson.observation(vsmLeak > 0.05
        ? "VSM's bound lets light through the lower occluder's shadow, by more than 0.05, along the upper occluder's "
          "shadow edge: light bleeding."
        : "VSM stays within 0.05 of PCF over the same texels here.");
    lesson.observation(lesson.value("lvsm", "/buffers/light_leak/mean") < lesson.value("vsm", "/buffers/light_leak/mean")
        ? "Layered VSM lets in less light than VSM over the image (its mean light_leak is lower): where the two "
          "occluders fall in different layers, the nearer one, clamped onto the layer's near end, adds no variance."
        : "Layered VSM does not let in less light than VSM over the image here.");
    lesson.observation(lesson.value("lvsm", "/buffers/light_leak/max") < vsmLeak
        ? "Its largest leak is below VSM's too."
        : "Its largest leak is not below VSM's: at a pixel whose box holds depths in front of its layer, clamping them "
          "onto the layer's near end, close to the receiver, can lift the bound above VSM's (`clamped_above_vsm` "
          "flags those pixels; the `lvsm` page measures them).");
    lesson.observation(lesson.value("msm", "/buffers/light_leak/max") < vsmLeak
        ? "MSM's largest leak is below VSM's: four moments pin the depth distribution down far more tightly than two."
        : "MSM's largest leak is not below VSM's here.");
    lesson.observation(lesson.value("csm-16", "/error/covered/rmse") < lesson.value("csm-4", "/error/covered/rmse")
        ? "CSM with 16 terms is closer to PCF than with 4: the truncated step is sharper and its umbra darker."
        : "CSM with 16 terms is not closer to PCF than with 4 here.");
    lesson.observation(lesson.value("csm-16", "/buffers/light_leak/mean") > lesson.value("msm", "/buffers/light_leak/mean")
        ? "Even with 16 terms, CSM lets in more light over the image than MSM: its umbrae keep the series' remainder."
        : "With 16 terms, CSM lets in no more light over the image than MSM here.");
    lesson.observation(lesson.value("csm-16-contact", "/error/covered/rmse") > lesson.value("msm-contact", "/error/covered/rmse")
        ? "At contact, CSM is further from PCF than MSM, even with 16 terms: its step is smeared over a share of the "
          "depth range, larger than the gap between the box and the ground next to it."
        : "At contact, CSM with 16 terms is not further from PCF than MSM here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sweep CSM's number of terms against the ray-traced reference:",
      "shadowlab bench datasets/contact/scene.json -t convsm --sweep terms=4,8,12,16 -r " + resolution +
        " --repeat 1 --reference-samples 64 --out out/csm-terms");
    lesson.tryNext("Sweep the number of layers of layered VSM:",
      "shadowlab bench datasets/stacked-occluders/scene.json -t lvsm --sweep layers=1,2,4,8 --set light_bleeding_reduction=0 -r " +
        resolution + " --repeat 1 --reference-samples 64 --out out/lvsm-layers");
    lesson.tryNext("Write the MSM run and look at its support depths and Hankel pivot in ParaView:",
      lesson.renderCommand("msm", "out/msm"));
  };
  return lesson;
}

} // namespace sl
