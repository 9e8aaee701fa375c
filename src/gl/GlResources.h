// Small helpers over VTK's OpenGL objects: render targets, read-back, GPU timers, the scene on the GPU.
#pragma once

#include "core/Image.h"
#include "scene/Scene.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLBufferObject;
class vtkOpenGLRenderTimer;
class vtkOpenGLRenderWindow;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkTextureObject;

namespace sl
{

// A float render target (R32F / RG32F / RGBA32F), nearest filtering, clamp to edge.
vtkSmartPointer<vtkTextureObject> makeFloatTarget(vtkOpenGLRenderWindow* window, int width, int height, int components);
// A 32-bit float depth target, nearest filtering, clamp to edge, no compare mode.
vtkSmartPointer<vtkTextureObject> makeDepthTarget(vtkOpenGLRenderWindow* window, int width, int height);
// GL_DEPTH32F_STENCIL8: the G-buffer's depth, which object-space techniques (shadow volumes) test against and
// write stencil into. Its depth is the same 32-bit float as makeDepthTarget's.
vtkSmartPointer<vtkTextureObject> makeDepthStencilTarget(vtkOpenGLRenderWindow* window, int width, int height);
// Multisampled variants (GL_TEXTURE_2D_MULTISAMPLE, fixed sample locations): read with texelFetch on a sampler2DMS.
vtkSmartPointer<vtkTextureObject> makeMultisampleFloatTarget(vtkOpenGLRenderWindow* window, int width, int height,
  int components, int samples);
vtkSmartPointer<vtkTextureObject> makeMultisampleDepthStencilTarget(vtkOpenGLRenderWindow* window, int width,
  int height, int samples);
// An RGBA8 target for the shaded image.
vtkSmartPointer<vtkTextureObject> makeColorTarget(vtkOpenGLRenderWindow* window, int width, int height);

// A raw R32UI 2-D array texture for image load/store and atomics (VTK 9.1's vtkTextureObject has no integer array
// textures with image binding): per-pixel counters and bit masks of the object-space techniques.
struct UintArrayTexture
{
  unsigned int handle = 0;
  int width = 0;
  int height = 0;
  int layers = 0;
  void allocate(int w, int h, int l); // keeps the texture when the size is unchanged (contents undefined)
  void release();
  std::vector<std::uint32_t> read() const; // layer after layer, rows bottom up
  // A per-pixel bit mask of `bits` light samples held 32 per layer (sample i: layer i / 32, bit i % 32), read back as
  // bits / 16 float components of 16 bits each (exact in a float): the light_sample_mask buffers.
  ImageF readSampleMask(int bits) const;
};

// Reads a whole texture back (glGetTextureImage). Row 0 is the bottom row.
ImageF readFloatTexture(vtkTextureObject* texture, int components);
ImageF readDepthTexture(vtkTextureObject* texture);
// Every layer of a 3D texture (one image for a 2D one).
std::vector<ImageF> readFloatTextureLayers(vtkTextureObject* texture, int components);
// An unsigned-integer texture (R32UI / RG32UI ...), exactly (tests compare integer tables bit for bit).
Image<std::uint32_t> readUnsignedTextureExact(vtkTextureObject* texture, int components);
ImageU8 readColorTexture(vtkTextureObject* texture); // RGB

// Throws GraphicsError naming `stage` if OpenGL recorded an error since the last check.
void checkGlErrors(const std::string& stage);

// Compiles (through VTK's shader cache) a program from embedded shader files; throws GraphicsError with
// the compiler log on failure. The program is bound on return.
vtkShaderProgram* readyProgram(vtkOpenGLRenderWindow* window, const std::string& vertexSource,
  const std::string& fragmentSource, const std::string& label);

// GPU time (GL_TIME_ELAPSED via vtkOpenGLRenderTimer) and wall time of a stage, summed over its runs since
// reset(): a stage runs once per frame, or once per sub-light when a technique splits the light (Yang et al.
// 2009 §5).
class StageTimer
{
public:
  StageTimer();
  ~StageTimer();
  void reset();
  void start();
  void stop(); // finishes the stage's GPU work and adds its times
  double gpuMilliseconds() const { return gpuMs_; }
  double wallMilliseconds() const { return wallMs_; }

private:
  std::unique_ptr<vtkOpenGLRenderTimer> timer_; // not a vtkObject
  std::chrono::steady_clock::time_point wallStart_;
  double gpuMs_ = 0.0;
  double wallMs_ = 0.0;
};

// GPU timestamps at the boundaries of a pass's steps (glQueryCounter): mark(0) before the first step, mark(i + 1)
// after step i; addTo reports each step's time as "<step>_gpu_ms" once every boundary of a frame was marked.
class StepTimestamps
{
public:
  explicit StepTimestamps(std::vector<std::string> steps);
  ~StepTimestamps();
  StepTimestamps(const StepTimestamps&) = delete;
  StepTimestamps& operator=(const StepTimestamps&) = delete;
  void mark(std::size_t boundary);
  void addTo(std::map<std::string, double>& statistics) const;
  void release();

private:
  std::vector<std::string> steps_;
  std::vector<unsigned int> queries_;
  bool complete_ = false;
};

// One scene object on the GPU: interleaved vertices (pWs xyz, nWs xyz, uv) + triangle indices, and the
// object's alpha texture when it has one.
struct GpuMesh
{
  vtkSmartPointer<vtkOpenGLBufferObject> vertices;
  vtkSmartPointer<vtkOpenGLBufferObject> indices;
  vtkSmartPointer<vtkTextureObject> alphaTexture; // null when the object is not perforated
  std::size_t indexCount = 0;
  const SceneObject* object = nullptr;
};

class GpuScene
{
public:
  GpuScene(vtkOpenGLRenderWindow* window, const Scene& scene);
  ~GpuScene();
  const std::vector<GpuMesh>& meshes() const { return meshes_; }
  // Distinct for every GpuScene ever made, so cached per-mesh state (VAOs) can tell scenes apart.
  std::uint64_t generation() const { return generation_; }
  void releaseGraphicsResources(vtkOpenGLRenderWindow* window);

private:
  std::vector<GpuMesh> meshes_;
  std::uint64_t generation_ = 0;
};

// Draws every mesh selected by `include` with `program`, binding attributes pWsIn/nWsIn/uvIn and the
// per-object uniforms the geometry shaders share (objectAlbedo, objectReceivesShadows, hasAlphaTexture,
// alphaTexture). The drawer caches one VAO per mesh, rebuilt when the program or the scene changes.
class MeshDrawer
{
public:
  MeshDrawer();
  ~MeshDrawer();
  template <typename Predicate>
  void draw(vtkShaderProgram* program, const GpuScene& scene, Predicate include);
  void releaseGraphicsResources(vtkOpenGLRenderWindow* window);

private:
  // `triangleBase`: the triangles of every mesh before this one in the scene (uniform meshTriangleBase, when used:
  // base + gl_PrimitiveID numbers every triangle of the scene once, for polygon-id shadow maps).
  void drawOne(vtkShaderProgram* program, const GpuMesh& mesh, std::size_t index, std::size_t triangleBase);
  std::vector<vtkSmartPointer<vtkOpenGLVertexArrayObject>> vaos_;
  vtkShaderProgram* boundProgram_ = nullptr;
  std::uint64_t sceneGeneration_ = 0;
};

template <typename Predicate>
void MeshDrawer::draw(vtkShaderProgram* program, const GpuScene& scene, Predicate include)
{
  if (scene.generation() != sceneGeneration_)
  {
    // VAOs point into the previous scene's buffers.
    releaseGraphicsResources(nullptr);
    sceneGeneration_ = scene.generation();
  }
  std::size_t triangleBase = 0;
  for (std::size_t i = 0; i < scene.meshes().size(); ++i)
  {
    if (include(*scene.meshes()[i].object))
    {
      drawOne(program, scene.meshes()[i], i, triangleBase);
    }
    triangleBase += scene.meshes()[i].indexCount / 3;
  }
  boundProgram_ = program;
}

} // namespace sl
