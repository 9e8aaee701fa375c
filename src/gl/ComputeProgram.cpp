#include "gl/ComputeProgram.h"

#include "core/Error.h"

#include <glm/gtc/type_ptr.hpp>
#include <vtk_glew.h>

namespace sl
{

ComputeProgram::ComputeProgram(const std::string& source, const std::string& label)
{
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint compiled = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
  if (compiled != GL_TRUE)
  {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    glDeleteShader(shader);
    throw GraphicsError("cannot compile compute shader '" + label + "': " + log);
  }
  program_ = glCreateProgram();
  glAttachShader(program_, shader);
  glLinkProgram(program_);
  glDeleteShader(shader);
  GLint linked = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE)
  {
    char log[2048] = {};
    glGetProgramInfoLog(program_, sizeof(log), nullptr, log);
    glDeleteProgram(program_);
    throw GraphicsError("cannot link compute shader '" + label + "': " + log);
  }
}

ComputeProgram::~ComputeProgram()
{
  glDeleteProgram(program_);
}

void ComputeProgram::use() const
{
  glUseProgram(program_);
}

void ComputeProgram::setInt(const char* name, int value) const
{
  glProgramUniform1i(program_, glGetUniformLocation(program_, name), value);
}

void ComputeProgram::setFloat(const char* name, double value) const
{
  glProgramUniform1f(program_, glGetUniformLocation(program_, name), static_cast<float>(value));
}

void ComputeProgram::setVector(const char* name, const glm::dvec3& value) const
{
  const glm::vec3 single(value);
  glProgramUniform3fv(program_, glGetUniformLocation(program_, name), 1, glm::value_ptr(single));
}

void ComputeProgram::setFloats(const char* name, const std::vector<double>& values) const
{
  const std::vector<float> single(values.begin(), values.end());
  if (!single.empty())
  {
    glProgramUniform1fv(program_, glGetUniformLocation(program_, name), static_cast<GLsizei>(single.size()), single.data());
  }
}

void ComputeProgram::setVectors(const char* name, const std::vector<glm::dvec4>& values) const
{
  std::vector<glm::vec4> single(values.begin(), values.end());
  if (!single.empty())
  {
    glProgramUniform4fv(program_, glGetUniformLocation(program_, name), static_cast<GLsizei>(single.size()),
      glm::value_ptr(single.front()));
  }
}

void ComputeProgram::setMatrices(const char* name, const std::vector<glm::dmat4>& values) const
{
  std::vector<glm::mat4> single(values.begin(), values.end());
  if (!single.empty())
  {
    glProgramUniformMatrix4fv(program_, glGetUniformLocation(program_, name), static_cast<GLsizei>(single.size()),
      GL_FALSE, glm::value_ptr(single.front()));
  }
}

void ComputeProgram::setMatrix(const char* name, const glm::dmat4& value) const
{
  const glm::mat4 single(value);
  glProgramUniformMatrix4fv(program_, glGetUniformLocation(program_, name), 1, GL_FALSE, glm::value_ptr(single));
}

void ComputeProgram::dispatch(glm::ivec2 groups) const
{
  dispatch(glm::ivec3(groups, 1));
}

void ComputeProgram::dispatch(glm::ivec3 groups) const
{
  glDispatchCompute(static_cast<GLuint>(groups.x), static_cast<GLuint>(groups.y), static_cast<GLuint>(groups.z));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

StorageBuffer::StorageBuffer(std::size_t words)
  : words_(words)
{
  glCreateBuffers(1, &buffer_);
  glNamedBufferData(buffer_, static_cast<GLsizeiptr>(words * sizeof(std::uint32_t)), nullptr, GL_DYNAMIC_READ);
}

StorageBuffer::~StorageBuffer()
{
  glDeleteBuffers(1, &buffer_);
}

void StorageBuffer::upload(const std::vector<std::uint32_t>& words) const
{
  upload(words.data(), words.size() * sizeof(std::uint32_t));
}

void StorageBuffer::upload(const void* data, std::size_t bytes) const
{
  SL_CHECK(bytes == words_ * sizeof(std::uint32_t));
  glNamedBufferSubData(buffer_, 0, static_cast<GLsizeiptr>(bytes), data);
}

void StorageBuffer::clear() const
{
  const GLuint zero = 0;
  glClearNamedBufferData(buffer_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

std::vector<std::uint32_t> StorageBuffer::download() const
{
  std::vector<std::uint32_t> words(words_);
  glGetNamedBufferSubData(buffer_, 0, static_cast<GLsizeiptr>(words.size() * sizeof(std::uint32_t)), words.data());
  return words;
}

void StorageBuffer::copyToTexture(
  unsigned int texture, int row, int width, int rows, unsigned int format, unsigned int type) const
{
  // Rows packed one after the other from the buffer's start, whatever unpack state VTK left; restored after.
  const GLenum unpackState[] = { GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_ALIGNMENT };
  const GLint packed[] = { 0, 0, 0, 4 };
  GLint saved[4] = {};
  for (int k = 0; k < 4; ++k)
  {
    glGetIntegerv(unpackState[k], &saved[k]);
    glPixelStorei(unpackState[k], packed[k]);
  }
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer_);
  glTextureSubImage2D(texture, 0, 0, row, width, rows, format, type, nullptr);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (int k = 0; k < 4; ++k)
  {
    glPixelStorei(unpackState[k], saved[k]);
  }
}

void StorageBuffer::bind(unsigned int binding) const
{
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_);
}

} // namespace sl
