#include "gl/GlResources.h"

#include "core/Error.h"

#include <algorithm>

#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLRenderTimer.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

namespace sl
{
namespace
{

void setNearestClamp(vtkTextureObject* texture)
{
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
}

const char* glErrorName(GLenum error)
{
  switch (error)
  {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
  }
}

} // namespace

vtkSmartPointer<vtkTextureObject> makeFloatTarget(vtkOpenGLRenderWindow* window, int width, int height, int components)
{
  static const unsigned internalFormats[] = { 0, GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F };
  static const unsigned formats[] = { 0, GL_RED, GL_RG, GL_RGB, GL_RGBA };
  SL_CHECK(components >= 1 && components <= 4);
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetInternalFormat(internalFormats[components]);
  texture->SetFormat(formats[components]);
  texture->SetDataType(GL_FLOAT);
  setNearestClamp(texture);
  if (!texture->Allocate2D(width, height, components, VTK_FLOAT))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " float render target"));
  }
  return texture;
}

vtkSmartPointer<vtkTextureObject> makeDepthTarget(vtkOpenGLRenderWindow* window, int width, int height)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  setNearestClamp(texture);
  if (!texture->AllocateDepth(width, height, vtkTextureObject::Float32))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " depth target"));
  }
  return texture;
}

vtkSmartPointer<vtkTextureObject> makeDepthStencilTarget(vtkOpenGLRenderWindow* window, int width, int height)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  setNearestClamp(texture);
  if (!texture->AllocateDepthStencil(width, height))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " depth-stencil target"));
  }
  return texture;
}

vtkSmartPointer<vtkTextureObject> makeMultisampleFloatTarget(vtkOpenGLRenderWindow* window, int width, int height,
  int components, int samples)
{
  static const unsigned internalFormats[] = { 0, GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F };
  static const unsigned formats[] = { 0, GL_RED, GL_RG, GL_RGB, GL_RGBA };
  SL_CHECK(components >= 1 && components <= 4 && samples > 1);
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetSamples(static_cast<unsigned>(samples));
  texture->SetInternalFormat(internalFormats[components]);
  texture->SetFormat(formats[components]);
  texture->SetDataType(GL_FLOAT);
  if (!texture->Allocate2D(width, height, components, VTK_FLOAT))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " ", samples, "x multisampled float target"));
  }
  return texture;
}

vtkSmartPointer<vtkTextureObject> makeMultisampleDepthStencilTarget(vtkOpenGLRenderWindow* window, int width,
  int height, int samples)
{
  SL_CHECK(samples > 1);
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetSamples(static_cast<unsigned>(samples));
  if (!texture->AllocateDepthStencil(width, height))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " ", samples, "x multisampled depth-stencil target"));
  }
  return texture;
}

void UintArrayTexture::allocate(int w, int h, int l)
{
  if (handle != 0 && width == w && height == h && layers == l)
  {
    return;
  }
  release();
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &handle);
  glTextureStorage3D(handle, 1, GL_R32UI, w, h, l);
  width = w;
  height = h;
  layers = l;
}

void UintArrayTexture::release()
{
  if (handle != 0)
  {
    glDeleteTextures(1, &handle);
    handle = 0;
  }
}

std::vector<std::uint32_t> UintArrayTexture::read() const
{
  std::vector<std::uint32_t> words(static_cast<std::size_t>(width) * height * layers);
  glGetTextureImage(handle, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(words.size() * sizeof(std::uint32_t)),
    words.data());
  return words;
}

ImageF UintArrayTexture::readSampleMask(int bits) const
{
  SL_CHECK(bits % 16 == 0 && (bits + 31) / 32 <= layers);
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::vector<std::uint32_t> words = read();
  const int chunks = bits / 16;
  ImageF mask(width, height, chunks);
  for (std::size_t pixel = 0; pixel < pixels; ++pixel)
  {
    for (int chunk = 0; chunk < chunks; ++chunk)
    {
      const std::uint32_t word = words[static_cast<std::size_t>(chunk / 2) * pixels + pixel];
      mask.data[pixel * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(chunk)] =
        static_cast<float>((word >> (16 * (chunk % 2))) & 0xFFFFu);
    }
  }
  return mask;
}

StepTimestamps::StepTimestamps(std::vector<std::string> steps)
  : steps_(std::move(steps))
{
}

StepTimestamps::~StepTimestamps() = default; // the queries go with the context: release() while it is current

void StepTimestamps::mark(std::size_t boundary)
{
  SL_CHECK(boundary <= steps_.size());
  if (queries_.empty())
  {
    queries_.resize(steps_.size() + 1);
    glGenQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
  }
  glQueryCounter(queries_[boundary], GL_TIMESTAMP);
  complete_ = boundary == steps_.size();
}

void StepTimestamps::addTo(std::map<std::string, double>& statistics) const
{
  if (!complete_)
  {
    return;
  }
  std::vector<GLuint64> times(queries_.size());
  for (std::size_t k = 0; k < times.size(); ++k)
  {
    glGetQueryObjectui64v(queries_[k], GL_QUERY_RESULT, &times[k]);
  }
  for (std::size_t step = 0; step < steps_.size(); ++step)
  {
    statistics[steps_[step] + "_gpu_ms"] = 1e-6 * static_cast<double>(times[step + 1] - times[step]);
  }
}

void StepTimestamps::release()
{
  if (!queries_.empty())
  {
    glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    queries_.clear();
  }
  complete_ = false;
}

vtkSmartPointer<vtkTextureObject> makeColorTarget(vtkOpenGLRenderWindow* window, int width, int height)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(window);
  texture->SetInternalFormat(GL_RGBA8);
  texture->SetFormat(GL_RGBA);
  texture->SetDataType(GL_UNSIGNED_BYTE);
  setNearestClamp(texture);
  if (!texture->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR))
  {
    throw GraphicsError(format("cannot allocate a ", width, "x", height, " colour target"));
  }
  return texture;
}

ImageF readFloatTexture(vtkTextureObject* texture, int components)
{
  static const GLenum formats[] = { 0, GL_RED, GL_RG, GL_RGB, GL_RGBA };
  ImageF image(static_cast<int>(texture->GetWidth()), static_cast<int>(texture->GetHeight()), components);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture->GetHandle(), 0, formats[components], GL_FLOAT,
    static_cast<GLsizei>(image.data.size() * sizeof(float)), image.data.data());
  checkGlErrors("texture read-back");
  return image;
}

std::vector<ImageF> readFloatTextureLayers(vtkTextureObject* texture, int components)
{
  static const GLenum formats[] = { 0, GL_RED, GL_RG, GL_RGB, GL_RGBA };
  const int width = static_cast<int>(texture->GetWidth());
  const int height = static_cast<int>(texture->GetHeight());
  const int layers = std::max(1, static_cast<int>(texture->GetDepth()));
  std::vector<float> data(static_cast<std::size_t>(width) * height * layers * components);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture->GetHandle(), 0, formats[components], GL_FLOAT,
    static_cast<GLsizei>(data.size() * sizeof(float)), data.data());
  checkGlErrors("texture read-back");
  std::vector<ImageF> images;
  const std::size_t layerValues = static_cast<std::size_t>(width) * height * components;
  for (int layer = 0; layer < layers; ++layer)
  {
    ImageF image(width, height, components);
    std::copy(data.begin() + layer * layerValues, data.begin() + (layer + 1) * layerValues, image.data.begin());
    images.push_back(std::move(image));
  }
  return images;
}

ImageF readDepthTexture(vtkTextureObject* texture)
{
  ImageF image(static_cast<int>(texture->GetWidth()), static_cast<int>(texture->GetHeight()), 1);
  glGetTextureImage(texture->GetHandle(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
    static_cast<GLsizei>(image.data.size() * sizeof(float)), image.data.data());
  checkGlErrors("depth read-back");
  return image;
}

Image<std::uint32_t> readUnsignedTextureExact(vtkTextureObject* texture, int components)
{
  static const GLenum formats[] = { 0, GL_RED_INTEGER, GL_RG_INTEGER, GL_RGB_INTEGER, GL_RGBA_INTEGER };
  Image<std::uint32_t> image(static_cast<int>(texture->GetWidth()), static_cast<int>(texture->GetHeight()), components);
  glGetTextureImage(texture->GetHandle(), 0, formats[components], GL_UNSIGNED_INT,
    static_cast<GLsizei>(image.data.size() * sizeof(std::uint32_t)), image.data.data());
  checkGlErrors("integer read-back");
  return image;
}

ImageU8 readColorTexture(vtkTextureObject* texture)
{
  ImageU8 rgba(static_cast<int>(texture->GetWidth()), static_cast<int>(texture->GetHeight()), 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture->GetHandle(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rgba.data.size()),
    rgba.data.data());
  checkGlErrors("colour read-back");
  ImageU8 rgb(rgba.width, rgba.height, 3);
  for (std::size_t i = 0; i < rgba.pixelCount(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb.data[i * 3 + c] = rgba.data[i * 4 + c];
    }
  }
  return rgb;
}

void checkGlErrors(const std::string& stage)
{
  std::string errors;
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError())
  {
    errors += (errors.empty() ? "" : ", ") + std::string(glErrorName(error));
  }
  if (!errors.empty())
  {
    throw GraphicsError("OpenGL error in " + stage + ": " + errors);
  }
}

vtkShaderProgram* readyProgram(vtkOpenGLRenderWindow* window, const std::string& vertexSource,
  const std::string& fragmentSource, const std::string& label)
{
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(vertexSource.c_str(), fragmentSource.c_str(), "");
  if (!program || !program->GetCompiled())
  {
    throw GraphicsError("cannot build shader program '" + label + "' (run with SHADOWLAB_VTK_LOG=full to see the GLSL compiler log)");
  }
  return program;
}

StageTimer::StageTimer()
  : timer_(std::make_unique<vtkOpenGLRenderTimer>())
{
}

StageTimer::~StageTimer() = default;

void StageTimer::reset()
{
  gpuMs_ = 0.0;
  wallMs_ = 0.0;
}

void StageTimer::start()
{
  timer_->Reset();
  wallStart_ = std::chrono::steady_clock::now();
  timer_->Start();
}

void StageTimer::stop()
{
  timer_->Stop();
  // Wall time of a stage includes finishing its GPU work, so the two are comparable; the query is then ready.
  glFinish();
  wallMs_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart_).count();
  while (!timer_->Ready())
  {
  }
  gpuMs_ += static_cast<double>(timer_->GetElapsedNanoseconds()) * 1e-6;
}

GpuScene::GpuScene(vtkOpenGLRenderWindow* window, const Scene& scene)
{
  static std::uint64_t nextGeneration = 1;
  generation_ = nextGeneration++;
  for (const SceneObject& object : scene.objects)
  {
    const TriangleMesh& mesh = object.mesh;
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions.size() * 8);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    {
      const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
      interleaved.insert(interleaved.end(), { mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z,
                                              mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z, uv.x, uv.y });
    }
    GpuMesh gpu;
    gpu.object = &object;
    gpu.vertices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    gpu.vertices->SetType(vtkOpenGLBufferObject::ArrayBuffer);
    gpu.indices = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    gpu.indices->SetType(vtkOpenGLBufferObject::ElementArrayBuffer);
    if (!gpu.vertices->Upload(interleaved, vtkOpenGLBufferObject::ArrayBuffer) ||
      !gpu.indices->Upload(mesh.indices, vtkOpenGLBufferObject::ElementArrayBuffer))
    {
      throw GraphicsError("cannot upload the geometry of " + object.name);
    }
    gpu.indexCount = mesh.indices.size();
    if (object.hasAlphaTexture)
    {
      const ImageF& alpha = object.alphaTexture.alpha;
      gpu.alphaTexture = vtkSmartPointer<vtkTextureObject>::New();
      gpu.alphaTexture->SetContext(window);
      gpu.alphaTexture->SetInternalFormat(GL_R32F);
      gpu.alphaTexture->SetFormat(GL_RED);
      gpu.alphaTexture->SetDataType(GL_FLOAT);
      gpu.alphaTexture->SetMinificationFilter(vtkTextureObject::Nearest);
      gpu.alphaTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
      gpu.alphaTexture->SetWrapS(vtkTextureObject::Repeat);
      gpu.alphaTexture->SetWrapT(vtkTextureObject::Repeat);
      void* pixels[1] = { const_cast<float*>(alpha.data.data()) };
      if (!gpu.alphaTexture->Create2DFromRaw(alpha.width, alpha.height, 1, VTK_FLOAT, pixels[0]))
      {
        throw GraphicsError("cannot upload the alpha texture of " + object.name);
      }
    }
    meshes_.push_back(std::move(gpu));
  }
}

GpuScene::~GpuScene() = default;

void GpuScene::releaseGraphicsResources(vtkOpenGLRenderWindow* window)
{
  for (GpuMesh& mesh : meshes_)
  {
    mesh.vertices->ReleaseGraphicsResources();
    mesh.indices->ReleaseGraphicsResources();
    if (mesh.alphaTexture)
    {
      mesh.alphaTexture->ReleaseGraphicsResources(window);
    }
  }
}

MeshDrawer::MeshDrawer() = default;
MeshDrawer::~MeshDrawer() = default;

void MeshDrawer::drawOne(vtkShaderProgram* program, const GpuMesh& mesh, std::size_t index, std::size_t triangleBase)
{
  if (vaos_.size() <= index)
  {
    vaos_.resize(index + 1);
  }
  auto& vao = vaos_[index];
  if (!vao || boundProgram_ != program)
  {
    // A VAO's attribute locations belong to one program; rebuild when the program changes.
    if (vao)
    {
      vao->ReleaseGraphicsResources();
    }
    vao = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
    vao->Bind();
    const int stride = 8 * sizeof(float);
    // Only attributes the program uses (the compiler drops the others, and VTK reports binding them).
    const struct
    {
      const char* name;
      int offsetFloats;
      int components;
    } attributes[] = { { "pWsIn", 0, 3 }, { "nWsIn", 3, 3 }, { "uvIn", 6, 2 } };
    for (const auto& attribute : attributes)
    {
      if (program->IsAttributeUsed(attribute.name))
      {
        vao->AddAttributeArray(program, mesh.vertices, attribute.name, attribute.offsetFloats * sizeof(float), stride,
          VTK_FLOAT, attribute.components, false);
      }
    }
  }
  vao->Bind();
  mesh.indices->Bind();
  const SceneObject& object = *mesh.object;
  const float albedo[3] = { static_cast<float>(object.material.albedo.x), static_cast<float>(object.material.albedo.y),
    static_cast<float>(object.material.albedo.z) };
  if (program->IsUniformUsed("objectAlbedo"))
  {
    program->SetUniform3f("objectAlbedo", albedo);
  }
  if (program->IsUniformUsed("objectReceivesShadows"))
  {
    program->SetUniformi("objectReceivesShadows", object.receiveShadows ? 1 : 0);
  }
  if (program->IsUniformUsed("meshTriangleBase"))
  {
    program->SetUniformi("meshTriangleBase", static_cast<int>(triangleBase));
  }
  if (program->IsUniformUsed("hasAlphaTexture"))
  {
    program->SetUniformi("hasAlphaTexture", mesh.alphaTexture ? 1 : 0);
  }
  if (mesh.alphaTexture)
  {
    mesh.alphaTexture->Activate();
    program->SetUniformi("alphaTexture", mesh.alphaTexture->GetTextureUnit());
  }
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indexCount), GL_UNSIGNED_INT, nullptr);
  if (mesh.alphaTexture)
  {
    mesh.alphaTexture->Deactivate();
  }
  vao->Release();
}

void MeshDrawer::releaseGraphicsResources(vtkOpenGLRenderWindow*)
{
  for (auto& vao : vaos_)
  {
    if (vao)
    {
      vao->ReleaseGraphicsResources();
    }
  }
  vaos_.clear();
  boundProgram_ = nullptr;
}

} // namespace sl
