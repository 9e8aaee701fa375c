#include "io/ImageIO.h"

#include "core/Error.h"
#include "passes/ShadowRenderer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <cstring>
#include <exception>

namespace sl
{

void writeVti(const std::filesystem::path& path, const std::vector<NamedImage>& images)
{
  SL_CHECK(!images.empty());
  vtkNew<vtkImageData> data;
  data->SetDimensions(images.front().image.width, images.front().image.height, 1);
  data->SetSpacing(1.0, 1.0, 1.0);
  data->SetOrigin(0.0, 0.0, 0.0);
  for (const NamedImage& named : images)
  {
    SL_CHECK(named.image.width == images.front().image.width && named.image.height == images.front().image.height);
    vtkNew<vtkFloatArray> array;
    array->SetName(named.name.c_str());
    array->SetNumberOfComponents(named.image.components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(named.image.pixelCount()));
    std::memcpy(array->GetPointer(0), named.image.data.data(), named.image.data.size() * sizeof(float));
    data->GetPointData()->AddArray(array);
  }
  data->GetPointData()->SetActiveScalars(images.front().name.c_str());
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.string().c_str());
  writer->SetInputData(data);
  writer->SetCompressorTypeToZLib();
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  if (writer->Write() != 1)
  {
    throw InputError(path.string() + ": cannot write the VTK image file");
  }
}

std::vector<NamedImage> readVti(const std::filesystem::path& path)
{
  if (!std::filesystem::is_regular_file(path))
  {
    throw InputError(path.string() + ": no such file");
  }
  vtkNew<vtkXMLImageDataReader> reader;
  if (!reader->CanReadFile(path.string().c_str()))
  {
    throw InputError(path.string() + ": not a VTK XML image file (.vti)");
  }
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dimensions[3];
  data->GetDimensions(dimensions);
  std::vector<NamedImage> images;
  vtkPointData* pointData = data->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (!array || !array->GetName())
    {
      continue;
    }
    NamedImage named;
    named.name = array->GetName();
    named.image = ImageF(dimensions[0], dimensions[1], array->GetNumberOfComponents());
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
    {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        named.image.data[static_cast<std::size_t>(t) * named.image.components + c] =
          static_cast<float>(array->GetComponent(t, c));
      }
    }
    images.push_back(std::move(named));
  }
  return images;
}

void writePng(const std::filesystem::path& path, const ImageU8& rgb)
{
  SL_CHECK(rgb.components == 3);
  vtkNew<vtkImageData> data;
  data->SetDimensions(rgb.width, rgb.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::memcpy(data->GetScalarPointer(), rgb.data.data(), rgb.data.size());
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.string().c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::is_regular_file(path))
  {
    throw InputError(path.string() + ": cannot write the PNG file");
  }
}

ImageU8 readPng(const std::filesystem::path& path)
{
  vtkNew<vtkPNGReader> reader;
  if (!std::filesystem::is_regular_file(path) || !reader->CanReadFile(path.string().c_str()))
  {
    throw InputError(path.string() + ": not a readable PNG file");
  }
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dimensions[3];
  data->GetDimensions(dimensions);
  const int components = data->GetNumberOfScalarComponents();
  ImageU8 rgb(dimensions[0], dimensions[1], 3);
  const auto* pixels = static_cast<const unsigned char*>(data->GetScalarPointer());
  for (std::size_t i = 0; i < rgb.pixelCount(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb.data[i * 3 + c] = pixels[i * components + std::min(c, components - 1)];
    }
  }
  return rgb;
}

void writeExr(const std::filesystem::path& path, const ImageF& values)
{
  SL_CHECK(values.components == 1);
  try
  {
    Imf::Header header(values.width, values.height);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.string().c_str(), header);
    // EXR rows run top to bottom; point the frame buffer at our last row and walk up (negative y stride).
    const std::size_t rowBytes = sizeof(float) * static_cast<std::size_t>(values.width);
    const char* lastRow = reinterpret_cast<const char*>(values.data.data()) + rowBytes * (values.height - 1);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, const_cast<char*>(lastRow), sizeof(float),
                              -static_cast<std::ptrdiff_t>(rowBytes)));
    file.setFrameBuffer(frameBuffer);
    file.writePixels(values.height);
  }
  catch (const std::exception& error)
  {
    throw InputError(path.string() + ": cannot write the OpenEXR file (" + error.what() + ")");
  }
}

ImageF readExr(const std::filesystem::path& path)
{
  try
  {
    Imf::InputFile file(path.string().c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    ImageF values(width, height, 1);
    const std::size_t rowBytes = sizeof(float) * static_cast<std::size_t>(width);
    char* lastRow = reinterpret_cast<char*>(values.data.data()) + rowBytes * (height - 1);
    // Slice base is addressed with the data window's origin: base + x * xStride + y * yStride.
    char* base = lastRow - static_cast<std::ptrdiff_t>(window.min.x) * static_cast<std::ptrdiff_t>(sizeof(float)) +
      static_cast<std::ptrdiff_t>(window.min.y) * static_cast<std::ptrdiff_t>(rowBytes);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, base, sizeof(float), -static_cast<std::ptrdiff_t>(rowBytes)));
    file.setFrameBuffer(frameBuffer);
    file.readPixels(window.min.y, window.max.y);
    return values;
  }
  catch (const std::exception& error)
  {
    throw InputError(path.string() + ": cannot read the OpenEXR file (" + error.what() + ")");
  }
}

} // namespace sl
