// A GLSL compute program (VTK 9.1's shader cache has no compute stage), with the shader-storage
// buffer a reduction writes its few results into. Throws GraphicsError with the compiler log on failure.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sl
{

class ComputeProgram
{
public:
  ComputeProgram(const std::string& source, const std::string& label);
  ~ComputeProgram();
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  void use() const;
  void setInt(const char* name, int value) const;
  void setFloat(const char* name, double value) const;
  void setVector(const char* name, const glm::dvec3& value) const;
  // A float uniform array from its element 0; nothing for an empty list.
  void setFloats(const char* name, const std::vector<double>& values) const;
  void setMatrix(const char* name, const glm::dmat4& value) const;
  // A uniform array from its element 0 (in float); nothing for an empty list.
  void setVectors(const char* name, const std::vector<glm::dvec4>& values) const;
  void setMatrices(const char* name, const std::vector<glm::dmat4>& values) const;
  // Runs groups.x * groups.y work groups and waits until their storage writes are visible.
  void dispatch(glm::ivec2 groups) const;
  void dispatch(glm::ivec3 groups) const;

private:
  unsigned int program_ = 0;
};

// A std430 buffer of 32-bit words bound at a storage binding point.
class StorageBuffer
{
public:
  explicit StorageBuffer(std::size_t words);
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;

  std::size_t words() const { return words_; }
  void upload(const std::vector<std::uint32_t>& words) const;
  // The whole buffer from any std430 data (a vec4 array, a struct array): `bytes` must be its size.
  void upload(const void* data, std::size_t bytes) const;
  // Every word to 0, on the GPU (no upload).
  void clear() const;
  std::vector<std::uint32_t> download() const;
  void bind(unsigned int binding) const;
  // Rows [row, row + rows) of level 0 of `texture` (a 2-D texture `width` texels wide) from the buffer's start, as
  // texels of `format` and `type` (a pixel unpack from the buffer, no round trip through the CPU).
  void copyToTexture(unsigned int texture, int row, int width, int rows, unsigned int format, unsigned int type) const;

private:
  unsigned int buffer_ = 0;
  std::size_t words_ = 0;
};

} // namespace sl
