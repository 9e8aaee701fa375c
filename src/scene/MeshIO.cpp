#include "scene/MeshIO.h"

#include "core/Error.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

namespace sl
{

namespace
{

using OpenMeshTriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Relative area threshold of MeshIO.h: twice the area below this times the longest edge squared is a
// triangle whose corners are collinear up to float rounding.
constexpr double kDegenerateAreaRatio = 1e-10;

// OpenMesh reports through its own global streams (omerr/omout/omlog) straight to the console. The loader
// must print nothing (problems become InputErrors), so the streams are muted for the duration of a read
// and restored afterwards, whatever state the rest of the program left them in.
class OpenMeshConsoleSilencer
{
public:
  OpenMeshConsoleSilencer()
    : wasEnabled_{ ::omerr().is_enabled(), ::omout().is_enabled(), ::omlog().is_enabled() }
  {
    for (OpenMesh::mostream* stream : streams())
      stream->disable();
  }
  ~OpenMeshConsoleSilencer()
  {
    const std::array<OpenMesh::mostream*, 3> all = streams();
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      // Flushing while disabled discards a half-written line instead of printing it later.
      all[i]->flush();
      if (wasEnabled_[i])
        all[i]->enable();
    }
  }
  OpenMeshConsoleSilencer(const OpenMeshConsoleSilencer&) = delete;
  OpenMeshConsoleSilencer& operator=(const OpenMeshConsoleSilencer&) = delete;

private:
  static std::array<OpenMesh::mostream*, 3> streams()
  {
    return { &::omerr(), &::omout(), &::omlog() };
  }
  std::array<bool, 3> wasEnabled_;
};

glm::dvec3 toDvec3(const OpenMeshTriMesh::Point& p)
{
  return { p[0], p[1], p[2] };
}

// True for a degenerate triangle (MeshIO.h); otherwise `areaNormal` receives its unnormalised normal, whose
// length is twice the area (the weight of an area-weighted vertex normal). Corners are finite (the reader
// refuses anything else) and come from floats, so no product here can overflow a double.
bool isDegenerate(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, glm::dvec3& areaNormal)
{
  areaNormal = glm::cross(b - a, c - a);
  const double longestEdgeSquared =
    std::max({ glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c) });
  return !(glm::length(areaNormal) > kDegenerateAreaRatio * longestEdgeSquared);
}

std::string quoted(const std::filesystem::path& file)
{
  return "'" + file.string() + "'";
}

// ---- what the file says about itself --------------------------------------------------------------------
// OpenMesh's readers skip what they cannot parse, or misread everything after it, without a word: an OBJ
// `v nan 0 0` line is dropped and every later index shifts; an ASCII PLY/OFF/STL number that does not parse
// leaves the rest of the file misaligned. So the text is scanned first and such a file is refused naming
// the line; and the element counts the file declares are compared with what OpenMesh delivered, so any
// skip that remains is an error too.

enum class MeshFormat
{
  Obj,
  Ply,
  Off,
  Stl,
  Other // whatever else OpenMesh reads (.om)
};

MeshFormat formatOf(const std::filesystem::path& file)
{
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj")
    return MeshFormat::Obj;
  if (extension == ".ply")
    return MeshFormat::Ply;
  if (extension == ".off")
    return MeshFormat::Off;
  if (extension == ".stl" || extension == ".stla" || extension == ".stlb")
    return MeshFormat::Stl;
  return MeshFormat::Other;
}

// What scanning a file found: the vertex and face counts it declares (PLY/OFF header, binary STL facet
// count, OBJ lines; -1 where unknown), and the triangles OpenMesh's OBJ reader removes before our importer
// sees the face (see scanObj).
struct FileScan
{
  long long vertices = -1;
  long long faces = -1;
  std::size_t repeatedCornerTriangles = 0;
};

// Reads a text file line by line, counting lines; a '#' starts a comment where `hashComments` is set.
class TextLines
{
public:
  TextLines(const std::filesystem::path& file, bool hashComments)
    : stream_(file, std::ios::binary)
    , hashComments_(hashComments)
  {
    if (!stream_)
      throw InputError(format("cannot read '", file.string(), "' (cannot open file)"));
  }
  // The next line's whitespace-separated tokens (views into the line, valid until the next call).
  bool next(std::vector<std::string_view>& tokens)
  {
    if (!std::getline(stream_, line_))
      return false;
    ++number_;
    std::string_view content = line_;
    if (hashComments_)
      content = content.substr(0, content.find('#'));
    tokens.clear();
    std::size_t start = 0;
    while ((start = content.find_first_not_of(" \t\r\f\v", start)) != std::string_view::npos)
    {
      const std::size_t end = std::min(content.find_first_of(" \t\r\f\v", start), content.size());
      tokens.push_back(content.substr(start, end - start));
      start = end;
    }
    return true;
  }
  long long number() const { return number_; }
  // Bytes consumed so far (the start of the next line).
  long double position() { return static_cast<long double>(static_cast<std::streamoff>(stream_.tellg())); }

private:
  std::ifstream stream_;
  bool hashComments_;
  std::string line_;
  long long number_ = 0;
};

bool parseCount(std::string_view token, long long& count)
{
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), count);
  return error == std::errc() && end == token.data() + token.size() && count >= 0;
}

// Empty when `token` is a number OpenMesh reads as a finite float (its points are Vec3f, and its text readers
// fail on a value beyond FLT_MAX); otherwise why not.
std::string numberProblem(std::string_view token)
{
  std::string_view digits = token;
  if (!digits.empty() && digits[0] == '+')
    digits.remove_prefix(1); // from_chars takes no '+'; some exporters write one
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || end != digits.data() + digits.size() ||
    (error != std::errc() && error != std::errc::result_out_of_range))
    return format("'", token, "' is not a number");
  if (error == std::errc::result_out_of_range)
  {
    // Overflow or underflow; an underflow reads as (nearly) zero, which is fine.
    if (std::abs(std::strtod(std::string(digits).c_str(), nullptr)) > 1.0)
      return format("'", token, "' is out of range");
    return {};
  }
  if (!std::isfinite(value))
    return format("'", token, "' is not a finite number");
  if (std::abs(value) > static_cast<double>(std::numeric_limits<float>::max()))
    return format("'", token, "' is out of range (beyond 32-bit float)");
  return {};
}

InputError lineError(const std::filesystem::path& file, long long lineNumber, const std::string& problem)
{
  return InputError(format(file.string(), ":", lineNumber, ": ", problem));
}

// Every token of an ASCII vertex record must be a finite number (coordinates, normals, colours alike).
void checkVertexNumbers(const std::filesystem::path& file, const TextLines& lines, long long vertex,
  const std::vector<std::string_view>& tokens, std::size_t count)
{
  for (std::size_t i = 0; i < std::min(count, tokens.size()); ++i)
    if (const std::string problem = numberProblem(tokens[i]); !problem.empty())
      throw lineError(file, lines.number(), format("vertex ", vertex, ": ", problem));
}

// Bytes of one value of a PLY scalar type (both spellings OpenMesh knows); 0 for a name it does not know.
int plyTypeSize(std::string_view type)
{
  static const std::array<std::pair<std::string_view, int>, 16> kSizes = { {
    { "char", 1 }, { "int8", 1 }, { "uchar", 1 }, { "uint8", 1 },
    { "short", 2 }, { "int16", 2 }, { "ushort", 2 }, { "uint16", 2 },
    { "int", 4 }, { "int32", 4 }, { "uint", 4 }, { "uint32", 4 },
    { "float", 4 }, { "float32", 4 }, { "double", 8 }, { "float64", 8 },
  } };
  for (const auto& [name, size] : kSizes)
    if (name == type)
      return size;
  return 0;
}

bool isPlyIntegerType(std::string_view type)
{
  return plyTypeSize(type) != 0 && type.substr(0, 5) != "float" && type != "double";
}

// One property of a PLY element: a scalar, or a list (a count, then that many values).
struct PlyProperty
{
  bool list = false;
  std::string countType; // lists only
  std::string valueType;
};

struct PlyElement
{
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
  long long binaryBytes = 0; // fixed-size properties and list counts: the least one element takes
};

// Why an ASCII PLY value of `type` is wrong, or empty. OpenMesh reads the values as a token stream with
// `operator>>`: a float where an integer belongs ("7.5") stops at the '.' and misaligns every value after it.
std::string plyValueProblem(std::string_view token, std::string_view type)
{
  if (!isPlyIntegerType(type))
    return numberProblem(token);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size())
    return format("'", token, "' is not an integer (", type, ")");
  return {};
}

// Checks an ASCII PLY body element by element, one element a line (as every exporter writes it): each line
// must hold exactly the values its properties call for, list lengths included. OpenMesh's reader takes the
// body as one token stream, so a line with more or fewer values shifts everything after it, and a negative
// list length becomes ~4e9 in its unsigned variable: it then reads (and stores) indices until memory runs
// out (a mutated bunny piece in tests/fuzz/regressions/mesh took 4 GB).
void scanPlyAsciiBody(const std::filesystem::path& file, TextLines& lines, const std::vector<PlyElement>& elements)
{
  std::vector<std::string_view> tokens;
  for (const PlyElement& element : elements)
  {
    for (long long index = 0; index < element.count; ++index)
    {
      do
      {
        if (!lines.next(tokens))
          throw InputError(format("'", file.string(), "': the PLY data ends after ", index, " of the ",
            element.count, " '", element.name, "' elements the header declares"));
      } while (tokens.empty());
      const auto problem = [&](const std::string& what) {
        return lineError(file, lines.number(), format(element.name, " ", index, ": ", what));
      };
      std::size_t next = 0; // the token the next value comes from
      bool complete = true; // every property found its values on this line
      for (const PlyProperty& property : element.properties)
      {
        long long values = 1;
        if (property.list)
        {
          if (next >= tokens.size())
          {
            complete = false;
            break;
          }
          if (!parseCount(tokens[next], values))
            throw problem(format("list length '", tokens[next], "' is not a non-negative integer"));
          ++next;
        }
        if (values > static_cast<long long>(tokens.size() - next))
        {
          complete = false;
          break;
        }
        for (long long i = 0; i < values; ++i, ++next)
          if (const std::string why = plyValueProblem(tokens[next], property.valueType); !why.empty())
            throw problem(why);
      }
      if (!complete || next != tokens.size())
        throw problem(format("the line holds ", tokens.size(), " values, ", complete ? "more" : "fewer",
          " than the header's properties call for (one element a line)"));
    }
  }
}

// Walks a binary PLY body: fixed-size properties are skipped, list lengths read (in the file's byte order),
// so a list longer than the rest of the file, or a negative length (which OpenMesh's unsigned variable takes
// as ~4e9 indices to read from a stream at its end), is refused before OpenMesh reads.
void scanPlyBinaryBody(const std::filesystem::path& file, std::uintmax_t bodyStart, std::uintmax_t fileSize,
  const std::vector<PlyElement>& elements, bool bigEndian)
{
  std::ifstream stream(file, std::ios::binary);
  stream.seekg(static_cast<std::streamoff>(bodyStart));
  std::uintmax_t remaining = fileSize - bodyStart;
  const auto truncated = [&](const PlyElement& element, long long index) {
    return InputError(format("'", file.string(), "': the PLY data ends inside ", element.name, " ", index,
      " (the header declares ", element.count, ")"));
  };
  const auto skip = [&](std::uintmax_t bytes, const PlyElement& element, long long index) {
    if (bytes > remaining)
      throw truncated(element, index);
    stream.ignore(static_cast<std::streamsize>(bytes));
    remaining -= bytes;
  };
  for (const PlyElement& element : elements)
  {
    const bool hasList = std::any_of(element.properties.begin(), element.properties.end(),
      [](const PlyProperty& property) { return property.list; });
    if (!hasList)
    {
      // Checked by the caller against the file size; skipped whole.
      skip(static_cast<std::uintmax_t>(element.count) * static_cast<std::uintmax_t>(element.binaryBytes), element, 0);
      continue;
    }
    for (long long index = 0; index < element.count; ++index)
    {
      for (const PlyProperty& property : element.properties)
      {
        if (!property.list)
        {
          skip(static_cast<std::uintmax_t>(plyTypeSize(property.valueType)), element, index);
          continue;
        }
        const int countSize = plyTypeSize(property.countType);
        std::array<unsigned char, 8> bytes{};
        if (static_cast<std::uintmax_t>(countSize) > remaining ||
          !stream.read(reinterpret_cast<char*>(bytes.data()), countSize))
          throw truncated(element, index);
        remaining -= static_cast<std::uintmax_t>(countSize);
        std::uint64_t length = 0;
        for (int i = 0; i < countSize; ++i)
          length |= std::uint64_t{ bytes[static_cast<std::size_t>(bigEndian ? countSize - 1 - i : i)] } << (8 * i);
        const bool isSigned = property.countType[0] != 'u';
        if (isSigned && (length >> (8 * countSize - 1)) != 0)
          throw InputError(format("'", file.string(), "': ", element.name, " ", index, " has a negative list length"));
        skip(length * static_cast<std::uintmax_t>(plyTypeSize(property.valueType)), element, index);
      }
    }
  }
}

FileScan scanPly(const std::filesystem::path& file)
{
  // The header is checked in full first, strictly line by line: OpenMesh's PLY reader crashes on a property
  // line before any element, loops forever on an unknown list type, a format line with other than version
  // 1.0 (or NUL bytes before it) and a header without elements (all found by fuzzing), and it reserves
  // memory for the declared counts (a 4e9-vertex header in a 229-byte file).
  TextLines lines(file, false);
  std::vector<std::string_view> tokens;
  const auto headerError = [&](const std::string& problem) {
    return lineError(file, lines.number(), "PLY header: " + problem);
  };
  if (!lines.next(tokens) || tokens.size() != 1 || tokens[0] != "ply")
    throw InputError(
      format("cannot read '", file.string(), "' (corrupt or not a PLY file: the first line is not 'ply')"));
  std::vector<PlyElement> elements;
  std::string formatName;
  bool headerEnded = false;
  while (!headerEnded && lines.next(tokens))
  {
    if (lines.number() > 10000)
      throw headerError("no end_header in the first 10000 lines");
    // A control character (a NUL byte, say) belongs in no header line, not even a comment: it is binary data
    // where the text header should be.
    for (const std::string_view token : tokens)
      if (std::any_of(token.begin(), token.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw headerError("control character in the header");
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info")
      continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header")
    {
      if (tokens.size() != 1)
        throw headerError("text after end_header");
      headerEnded = true;
    }
    else if (keyword == "format")
    {
      if (tokens.size() != 3 ||
        (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian") ||
        tokens[2] != "1.0")
        throw headerError("unknown format line (expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0')");
      if (!formatName.empty())
        throw headerError("second format line");
      formatName = std::string(tokens[1]);
    }
    else if (keyword == "element")
    {
      long long count = 0;
      if (tokens.size() != 3 || !parseCount(tokens[2], count))
        throw headerError("malformed element line (expected 'element <name> <count>')");
      elements.push_back({ std::string(tokens[1]), count, {}, 0 });
    }
    else if (keyword == "property")
    {
      if (elements.empty())
        throw headerError("property before any element");
      PlyElement& element = elements.back();
      if (tokens.size() == 3 && plyTypeSize(tokens[1]) != 0)
      {
        element.binaryBytes += plyTypeSize(tokens[1]);
        element.properties.push_back({ false, {}, std::string(tokens[1]) });
      }
      else if (tokens.size() == 5 && tokens[1] == "list" && isPlyIntegerType(tokens[2]) && plyTypeSize(tokens[3]) != 0)
      {
        element.binaryBytes += plyTypeSize(tokens[2]);
        element.properties.push_back({ true, std::string(tokens[2]), std::string(tokens[3]) });
      }
      else
        throw headerError("malformed property line or unknown type (expected 'property <type> <name>' or "
                          "'property list <integer type> <type> <name>')");
    }
    else
    {
      throw headerError(format("unknown header line '", keyword, "'"));
    }
  }
  if (!headerEnded)
    throw headerError("no end_header");
  if (formatName.empty())
    throw headerError("no format line");
  const auto vertexElement =
    std::find_if(elements.begin(), elements.end(), [](const PlyElement& element) { return element.name == "vertex"; });
  if (vertexElement == elements.end())
    throw headerError("no 'element vertex' line");
  if (std::any_of(elements.begin(), elements.end(), [](const PlyElement& element) {
        return element.count > 0 && element.properties.empty();
      }))
    throw headerError("an element with a count but no properties");
  const bool ascii = formatName == "ascii";

  // Every element takes at least one byte per property in ASCII (a digit; separators come on top) and its
  // fixed-size part in binary, so counts the rest of the file cannot hold are refused before anything else.
  std::error_code error;
  const std::uintmax_t fileSize = std::filesystem::file_size(file, error);
  if (error)
    throw InputError(format("cannot read '", file.string(), "' (", error.message(), ")"));
  // tellg() is -1 once the header's last line hit the end of the file: then no bytes follow it.
  const long double headerEnd = lines.position();
  const long double bodyStart = headerEnd < 0.0L ? static_cast<long double>(fileSize) : headerEnd;
  const long double dataBytes = static_cast<long double>(fileSize) - bodyStart;
  long double leastBytes = 0.0L;
  for (const PlyElement& element : elements)
    leastBytes += static_cast<long double>(element.count) *
      static_cast<long double>(std::max<long long>(1,
        ascii ? static_cast<long long>(element.properties.size()) : element.binaryBytes));
  if (leastBytes > dataBytes)
    throw InputError(format("'", file.string(), "': the PLY header declares more elements than the ",
      static_cast<long long>(dataBytes), " bytes after it can hold (", elements.front().count, " ",
      elements.front().name, elements.size() > 1 ? ", ..." : "", ")"));

  FileScan scan;
  for (const PlyElement& element : elements)
  {
    if (element.name == "vertex")
      scan.vertices = element.count;
    if (element.name == "face")
      scan.faces = element.count;
  }
  if (ascii)
    scanPlyAsciiBody(file, lines, elements);
  else
    scanPlyBinaryBody(file, static_cast<std::uintmax_t>(bodyStart), fileSize, elements,
      formatName == "binary_big_endian");
  return scan;
}

FileScan scanOff(const std::filesystem::path& file)
{
  // "[ST][C][N][4][n]OFF" alone on the first line, then "vertices faces edges", then one vertex per line
  // (x y z, normal with N, maybe a colour with C, texture coordinates with ST), then one face per line
  // ("n i1 .. in", maybe a colour with C); '#' comments allowed.
  TextLines lines(file, true);
  std::vector<std::string_view> tokens;
  lines.next(tokens);
  // OpenMesh takes any first word starting with an OFF keyword and then reads counts out of whatever
  // follows, reserving memory for them (a garbage header asked for 13 GB); so the keyword must be exact.
  static const std::regex keyword(R"(^(ST)?C?N?4?n?OFF$)");
  if (tokens.empty() || !std::regex_match(std::string(tokens[0]), keyword))
    throw InputError(format("cannot read '", file.string(), "' (corrupt or not an OFF file: the first word is '",
      tokens.empty() ? std::string_view() : tokens[0].substr(0, 40), "')"));
  const std::string offKeyword(tokens[0]);
  FileScan scan;
  if (offKeyword.find_first_of("4n") != std::string::npos || (tokens.size() == 2 && tokens[1] == "BINARY"))
    return scan; // dimension variants (OpenMesh refuses them) and binary OFF: left to OpenMesh
  // OpenMesh skips the rest of the keyword's line and reads the counts after it: counts on that line
  // ("OFF 1" in a fuzzed file) mean it takes the next numbers as counts, and then face lengths out of
  // vertex data, one of them -1, i.e. 4e9 indices to read.
  if (tokens.size() != 1)
    throw lineError(file, lines.number(), "OFF header: the keyword must be alone on the first line (the vertex, "
                                          "face and edge counts go on the next one)");
  do
  {
    if (!lines.next(tokens) || lines.number() > 1000)
      throw lineError(file, lines.number(), "OFF header: expected the vertex, face and edge counts");
  } while (tokens.empty());
  long long edges = 0;
  if (tokens.size() != 3 || !parseCount(tokens[0], scan.vertices) || !parseCount(tokens[1], scan.faces) ||
    !parseCount(tokens[2], edges))
    throw lineError(file, lines.number(), "OFF header: expected the vertex, face and edge counts");
  // An ASCII vertex takes at least 6 bytes ("0 0 0\n"), a face at least 2: refuse counts the file cannot
  // hold before OpenMesh reserves memory for them.
  std::error_code error;
  const std::uintmax_t fileSize = std::filesystem::file_size(file, error);
  if (!error && 6.0L * scan.vertices + 2.0L * scan.faces > static_cast<long double>(fileSize))
    throw InputError(format("'", file.string(), "': the OFF header declares ", scan.vertices, " vertices and ",
      scan.faces, " faces, more than its ", fileSize, " bytes can hold"));

  // OpenMesh reads the numbers it needs with operator>>, whatever line they are on, and only then the rest
  // of the line: a line with too few numbers shifts everything after it (a face length read from the wrong
  // place, or negative and so ~4e9 in its unsigned variable, makes it read indices until memory runs out).
  const bool hasNormal = offKeyword.find('N') != std::string::npos;
  const bool hasColour = offKeyword.find('C') != std::string::npos;
  const std::size_t vertexNumbers = 3 + (hasNormal ? 3 : 0);
  const auto nextLine = [&](const char* what, long long index, long long count) {
    do
    {
      if (!lines.next(tokens))
        throw InputError(format("'", file.string(), "': the OFF data ends after ", index, " of the ", count, " ", what,
          " the header declares"));
    } while (tokens.empty());
  };
  for (long long vertex = 0; vertex < scan.vertices; ++vertex)
  {
    nextLine("vertices", vertex, scan.vertices);
    if (tokens.size() < vertexNumbers)
      throw lineError(file, lines.number(),
        format("vertex ", vertex, ": needs ", vertexNumbers, " numbers, got ", tokens.size()));
    checkVertexNumbers(file, lines, vertex, tokens, vertexNumbers);
  }
  for (long long face = 0; face < scan.faces; ++face)
  {
    nextLine("faces", face, scan.faces);
    long long corners = 0;
    if (!parseCount(tokens[0], corners))
      throw lineError(file, lines.number(), format("face ", face, ": corner count '", tokens[0],
        "' is not a non-negative integer"));
    // Only a colour (C files) may follow the indices: OpenMesh reads anything else as the next face.
    const std::size_t values = tokens.size() - 1;
    if (values < static_cast<std::size_t>(corners) || (!hasColour && values != static_cast<std::size_t>(corners)))
      throw lineError(file, lines.number(),
        format("face ", face, ": ", corners, " corners, but ", values, " numbers follow"));
    for (std::size_t i = 1; i <= static_cast<std::size_t>(corners); ++i)
    {
      long long index = 0;
      if (!parseCount(tokens[i], index))
        throw lineError(file, lines.number(), format("face ", face, ": vertex index '", tokens[i],
          "' is not a non-negative integer"));
    }
  }
  return scan;
}

FileScan scanStl(const std::filesystem::path& file)
{
  // Binary STL: 80-byte header, uint32 little-endian facet count, 50 bytes per facet; OpenMesh takes a file
  // of exactly that size as binary. Otherwise ASCII, whose "vertex x y z" lines we check. Only facets can be
  // compared: STL repeats shared corners and OpenMesh merges them.
  FileScan scan;
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  {
    std::ifstream stream(file, std::ios::binary);
    std::array<unsigned char, 84> header{};
    if (!error && stream.read(reinterpret_cast<char*>(header.data()), header.size()))
    {
      const std::uint32_t facets = std::uint32_t{ header[80] } | (std::uint32_t{ header[81] } << 8) |
        (std::uint32_t{ header[82] } << 16) | (std::uint32_t{ header[83] } << 24);
      if (size == 84 + 50 * std::uintmax_t{ facets })
      {
        // OpenMesh merges equal corners through a std::map, where a NaN compares equivalent to some other
        // point: the corner would silently become another vertex. So the corners are checked here.
        std::array<unsigned char, 50> record{};
        for (std::uint32_t facet = 0; facet < facets && stream.read(reinterpret_cast<char*>(record.data()), 50);
             ++facet)
        {
          std::array<float, 9> corners{}; // after the 12-byte facet normal; STL is little-endian, as our hosts
          std::memcpy(corners.data(), record.data() + 12, sizeof(corners));
          for (std::size_t i = 0; i < corners.size(); ++i)
            if (!std::isfinite(corners[i]))
              throw InputError(format("'", file.string(), "': facet ", facet, " has a non-finite corner (",
                corners[i / 3 * 3], ", ", corners[i / 3 * 3 + 1], ", ", corners[i / 3 * 3 + 2], ")"));
        }
        scan.faces = facets;
        return scan;
      }
    }
  }
  TextLines lines(file, false);
  std::vector<std::string_view> tokens;
  while (lines.next(tokens))
  {
    if (tokens.empty() || tokens[0] != "vertex")
      continue;
    if (tokens.size() != 4)
      throw lineError(file, lines.number(), format("'vertex' needs 3 numbers, got ", tokens.size() - 1));
    for (std::size_t i = 1; i < tokens.size(); ++i)
      if (const std::string problem = numberProblem(tokens[i]); !problem.empty())
        throw lineError(file, lines.number(), format("'vertex' line: ", problem));
  }
  return scan;
}

// ---- OBJ line scanner -----------------------------------------------------------------------------------
// Accepts what OpenMesh's OBJ reader parses: coordinates that are finite 32-bit floats, 1-based indices, and
// negative indices relative to the elements defined so far.

// Why a face corner's index (vertex, texture coordinate or normal) is wrong, or empty; `resolved` receives
// the 1-based index. `definedSoFar` counts the elements of that kind above this line: a relative (negative)
// index must stay within them; a positive one beyond them is checked against the whole file by the caller.
std::string indexProblem(std::string_view token, const char* kind, long long definedSoFar, long long& resolved)
{
  long long index = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), index);
  if (token.empty() || error != std::errc() || end != token.data() + token.size())
    return format(kind, " index '", token, "' is not an integer");
  if (index == 0)
    return format(kind, " index 0 (OBJ indices start at 1)");
  if (index < 0)
  {
    resolved = definedSoFar + 1 + index;
    if (resolved < 1)
      return format("relative ", kind, " index ", index, " reaches before the first ", kind, " (", definedSoFar,
        " defined so far)");
    return {};
  }
  resolved = index;
  return {};
}

FileScan scanObj(const std::filesystem::path& file)
{
  TextLines lines(file, true);
  std::vector<std::string_view> tokens;
  struct ForwardReference // a positive index beyond the elements defined so far
  {
    long long lineNumber;
    std::size_t kind;
    long long index;
  };
  std::vector<ForwardReference> forwardReferences;
  constexpr std::array<const char*, 3> kKinds = { "vertex", "texture coordinate", "normal" };
  std::array<long long, 3> defined = { 0, 0, 0 }; // v, vt, vn lines so far
  FileScan scan;
  scan.faces = 0;
  std::vector<long long> faceVertices;
  while (lines.next(tokens))
  {
    if (tokens.empty())
      continue;
    const std::string_view keyword = tokens[0];
    const std::size_t numbers = tokens.size() - 1;
    if (keyword == "v" || keyword == "vt" || keyword == "vn")
    {
      // v: x y z, optionally w or an r g b colour; vt: u v [w]; vn: x y z. OpenMesh needs at least 2 (vt)
      // or 3 numbers and drops the line otherwise.
      const std::size_t minimum = keyword == "vt" ? 2 : 3;
      const std::size_t maximum = keyword == "v" ? 7 : 3;
      if (numbers < minimum || numbers > maximum)
        throw lineError(file, lines.number(),
          format("'", keyword, "' needs ", minimum == maximum ? "" : "at least ", minimum, " numbers, got ", numbers));
      for (std::size_t i = 1; i < tokens.size(); ++i)
        if (const std::string problem = numberProblem(tokens[i]); !problem.empty())
          throw lineError(file, lines.number(), format("'", keyword, "' line: ", problem));
      ++defined[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
    }
    else if (keyword == "f")
    {
      if (numbers < 3)
        throw lineError(file, lines.number(), format("a face needs at least 3 corners, got ", numbers));
      faceVertices.clear();
      for (std::size_t i = 1; i < tokens.size(); ++i)
      {
        // A corner is v, v/vt, v//vn or v/vt/vn.
        const std::string_view corner = tokens[i];
        const std::size_t firstSlash = corner.find('/');
        const std::size_t secondSlash =
          firstSlash == std::string_view::npos ? std::string_view::npos : corner.find('/', firstSlash + 1);
        const std::array<std::string_view, 3> parts = {
          corner.substr(0, firstSlash),
          firstSlash == std::string_view::npos ? std::string_view()
                                               : corner.substr(firstSlash + 1, secondSlash - firstSlash - 1),
          secondSlash == std::string_view::npos ? std::string_view() : corner.substr(secondSlash + 1),
        };
        for (std::size_t kind = 0; kind < parts.size(); ++kind)
        {
          if (kind > 0 && parts[kind].empty())
            continue; // texture coordinate and normal are optional
          long long resolved = 0;
          if (const std::string problem = indexProblem(parts[kind], kKinds[kind], defined[kind], resolved);
              !problem.empty())
            throw lineError(file, lines.number(), problem);
          if (resolved > defined[kind])
            forwardReferences.push_back({ lines.number(), kind, resolved });
          if (kind == 0)
            faceVertices.push_back(resolved);
        }
      }
      // OpenMesh's OBJ reader keeps the distinct corners of a face in order (`f 1 2 2 3` becomes the
      // triangle 1 2 3) and drops a face with fewer than 3 of them (`f 1 1 2`) before our importer sees it.
      // The n - max(distinct, 2) triangles that lose are degenerate ones, counted as such (MeshIO.h).
      std::sort(faceVertices.begin(), faceVertices.end());
      const auto distinct =
        static_cast<std::size_t>(std::unique(faceVertices.begin(), faceVertices.end()) - faceVertices.begin());
      scan.repeatedCornerTriangles += numbers - std::max<std::size_t>(distinct, 2);
      if (distinct >= 3)
        ++scan.faces;
    }
  }
  for (const ForwardReference& reference : forwardReferences)
    if (reference.index > defined[reference.kind])
      throw lineError(file, reference.lineNumber, format(kKinds[reference.kind], " index ", reference.index,
        " is out of range (the file has ", defined[reference.kind], ")"));
  scan.vertices = defined[0];
  return scan;
}

// ---- reading through OpenMesh ---------------------------------------------------------------------------

// OpenMesh's importer with the checks its readers leave out. It counts what the reader delivered (for the
// comparison with FileScan), refuses a face naming a vertex that does not exist (OpenMesh drops it
// silently), and takes a face naming the same vertex twice (PLY/OFF/STL `3 0 0 1`, which OpenMesh refuses) as
// degenerate: its n - 2 triangles are counted with the other degenerate triangles (MeshIO.h). (OBJ faces
// reach us without repeats: OpenMesh's OBJ reader removes them first, see scanObj.) Problems are recorded,
// not thrown, so no exception crosses OpenMesh's reader code; the first one is reported after it.
class CheckingImporter : public OpenMesh::IO::ImporterT<OpenMeshTriMesh>
{
public:
  using Base = OpenMesh::IO::ImporterT<OpenMeshTriMesh>;
  using VertexHandle = OpenMesh::VertexHandle;
  using FaceHandle = OpenMesh::FaceHandle;

  explicit CheckingImporter(OpenMeshTriMesh& mesh)
    : Base(mesh)
    , mesh_(mesh)
  {
  }

  VertexHandle add_vertex(const OpenMesh::Vec3f& point) override
  {
    ++verticesRead_;
    return Base::add_vertex(point);
  }
  VertexHandle add_vertex(const OpenMesh::Vec3d& point) override
  {
    ++verticesRead_;
    return Base::add_vertex(point);
  }
  VertexHandle add_vertex() override
  {
    ++verticesRead_;
    return Base::add_vertex();
  }

  using Base::add_face;
  FaceHandle add_face(const VHandles& corners) override
  {
    const long long face = facesRead_++;
    if (!problem_.empty())
      return FaceHandle();
    if (corners.size() < 3)
    {
      problem_ = format("face ", face, " has ", corners.size(), " corners (at least 3 needed)");
      return FaceHandle();
    }
    for (const VertexHandle corner : corners)
    {
      if (!mesh_.is_valid_handle(corner))
      {
        problem_ = format("face ", face, " uses vertex ", corner.idx(), ", but the file has ", mesh_.n_vertices(),
          " vertices (0 to ", static_cast<long long>(mesh_.n_vertices()) - 1, ")");
        return FaceHandle();
      }
    }
    for (std::size_t i = 0; i < corners.size(); ++i)
    {
      if (std::find(corners.begin() + static_cast<std::ptrdiff_t>(i) + 1, corners.end(), corners[i]) != corners.end())
      {
        // A fan over n corners has n - 2 triangles; with a repeated corner none of them can be kept whole.
        degenerateTriangles_ += corners.size() - 2;
        return FaceHandle();
      }
    }
    const std::size_t verticesBefore = mesh_.n_vertices();
    const FaceHandle added = Base::add_face(corners);
    // A face that would make the mesh non-manifold is added on fresh copies of its corners
    // (ImporterT::add_face), which get the point only; the file's normal and texture coordinate of each
    // corner are copied over once the reader has set them (finishVertexAttributes).
    if (mesh_.n_vertices() == verticesBefore + corners.size())
      for (std::size_t j = 0; j < corners.size(); ++j)
        copies_.emplace_back(VertexHandle(static_cast<int>(verticesBefore + j)), corners[j]);
    return added;
  }

  using Base::set_normal;
  void set_normal(VertexHandle vertex, const OpenMesh::Vec3f& normal) override
  {
    if (!existing(vertex, "a normal"))
      return;
    mark(normalSet_, vertex);
    Base::set_normal(vertex, normal);
  }
  void set_normal(VertexHandle vertex, const OpenMesh::Vec3d& normal) override
  {
    if (!existing(vertex, "a normal"))
      return;
    mark(normalSet_, vertex);
    Base::set_normal(vertex, normal);
  }
  using Base::set_texcoord;
  void set_texcoord(VertexHandle vertex, const OpenMesh::Vec2f& uv) override
  {
    if (!existing(vertex, "a texture coordinate"))
      return;
    mark(uvSet_, vertex);
    Base::set_texcoord(vertex, uv);
  }

  // After the read. OpenMesh's property arrays hold uninitialised values where the reader set nothing (STL
  // vertices have no normals, an OBJ vertex no face gave a `vt`, copies of non-manifold corners): copies
  // take their original's normal and texture coordinate, and whatever is still unset becomes zero (a zero
  // normal falls back to the computed one, MeshIO.h; a missing texture coordinate reads (0, 0)).
  void finishVertexAttributes()
  {
    for (const auto& [copy, original] : copies_)
    {
      if (isMarked(normalSet_, original))
      {
        mesh_.set_normal(copy, mesh_.normal(original));
        mark(normalSet_, copy);
      }
      if (isMarked(uvSet_, original))
      {
        mesh_.set_texcoord2D(copy, mesh_.texcoord2D(original));
        mark(uvSet_, copy);
      }
    }
    for (const VertexHandle vertex : mesh_.vertices())
    {
      if (!isMarked(normalSet_, vertex))
        mesh_.set_normal(vertex, OpenMeshTriMesh::Normal(0.0f, 0.0f, 0.0f));
      if (!isMarked(uvSet_, vertex))
        mesh_.set_texcoord2D(vertex, OpenMeshTriMesh::TexCoord2D(0.0f, 0.0f));
    }
  }
  bool anyNormalSet() const { return std::find(normalSet_.begin(), normalSet_.end(), true) != normalSet_.end(); }
  bool anyUvSet() const { return std::find(uvSet_.begin(), uvSet_.end(), true) != uvSet_.end(); }

  long long verticesRead() const { return verticesRead_; }
  long long facesRead() const { return facesRead_; }
  std::size_t degenerateTriangles() const { return degenerateTriangles_; }
  const std::string& problem() const { return problem_; }

private:
  OpenMeshTriMesh& mesh_;
  long long verticesRead_ = 0;
  long long facesRead_ = 0;
  std::size_t degenerateTriangles_ = 0;
  std::string problem_;
  std::vector<std::pair<VertexHandle, VertexHandle>> copies_; // (copy, original) of non-manifold corners
  std::vector<bool> normalSet_; // per vertex: the reader gave it a normal
  std::vector<bool> uvSet_;     // per vertex: the reader gave it a texture coordinate

  // OpenMesh's OBJ reader can hand an attribute to an invalid vertex handle (fuzzed: a face after an `l`
  // line); writing it would index the property arrays with -1. Such a file is refused instead.
  bool existing(VertexHandle vertex, const char* attribute)
  {
    if (vertex.is_valid() && static_cast<std::size_t>(vertex.idx()) < mesh_.n_vertices())
      return true;
    if (problem_.empty())
      problem_ = format("the reader gave ", attribute, " to vertex ", vertex.idx(), ", which does not exist");
    return false;
  }
  static void mark(std::vector<bool>& flags, VertexHandle vertex)
  {
    const auto index = static_cast<std::size_t>(vertex.idx());
    if (index >= flags.size())
      flags.resize(index + 1, false);
    flags[index] = true;
  }
  static bool isMarked(const std::vector<bool>& flags, VertexHandle vertex)
  {
    const auto index = static_cast<std::size_t>(vertex.idx());
    return index < flags.size() && flags[index];
  }
};

std::string describe(const OpenMeshTriMesh::Point& p)
{
  return format("(", p[0], ", ", p[1], ", ", p[2], ")");
}

struct OpenMeshRead
{
  std::size_t repeatedCornerTriangles = 0; // dropped because a face repeated a vertex
  bool fileHasNormals = false;             // the reader set vertex normals (unset ones are zero)
  bool fileHasUvs = false;                 // the reader set texture coordinates (unset ones are (0, 0))
};

// Reads `file` into `mesh`, refusing what MeshIO.h lists.
OpenMeshRead readWithOpenMesh(const std::filesystem::path& file, OpenMeshTriMesh& mesh)
{
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    throw InputError(format("cannot read ", quoted(file), " (no such file)"));
  if (!std::filesystem::is_regular_file(file, error))
    throw InputError(format("cannot read ", quoted(file), " (not a regular file)"));

  // Throws naming the line when the text holds something OpenMesh would skip or misread.
  FileScan scan;
  switch (formatOf(file))
  {
  case MeshFormat::Obj:
    scan = scanObj(file);
    break;
  case MeshFormat::Ply:
    scan = scanPly(file);
    break;
  case MeshFormat::Off:
    scan = scanOff(file);
    break;
  case MeshFormat::Stl:
    scan = scanStl(file);
    break;
  case MeshFormat::Other:
    break;
  }

  mesh.request_vertex_normals();
  mesh.request_vertex_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexNormal | OpenMesh::IO::Options::VertexTexCoord;
  CheckingImporter importer(mesh);
  bool readOk = false;
  try
  {
    const OpenMeshConsoleSilencer silencer;
    readOk = OpenMesh::IO::IOManager().read(file.string(), importer, options);
  }
  catch (const std::exception& e)
  {
    throw InputError(format("cannot read ", quoted(file), " (", e.what(), ")"));
  }
  if (!readOk)
    throw InputError(format("cannot read ", quoted(file), " (unsupported format or corrupt file)"));
  if (!importer.problem().empty())
    throw InputError(format(quoted(file), ": ", importer.problem()));
  if (scan.vertices >= 0 && importer.verticesRead() != scan.vertices)
    throw InputError(format(quoted(file), ": OpenMesh read ", importer.verticesRead(), " of the ", scan.vertices,
      " vertices the file declares (corrupt or unsupported vertex data)"));
  if (scan.faces >= 0 && importer.facesRead() != scan.faces)
    throw InputError(format(quoted(file), ": OpenMesh read ", importer.facesRead(), " of the ", scan.faces,
      " faces the file declares (corrupt or unsupported face data)"));

  importer.finishVertexAttributes();

  // Every reader, whatever its format: a coordinate, file normal or texture coordinate that is not finite
  // is an error naming the vertex (its index in file order; STL numbers its distinct corners in order of
  // appearance). Unset normals and texture coordinates are zero by now.
  for (const OpenMeshTriMesh::VertexHandle vertex : mesh.vertices())
  {
    const OpenMeshTriMesh::Point& point = mesh.point(vertex);
    if (!std::isfinite(point[0]) || !std::isfinite(point[1]) || !std::isfinite(point[2]))
      throw InputError(
        format(quoted(file), ": vertex ", vertex.idx(), " has a non-finite coordinate ", describe(point)));
    const OpenMeshTriMesh::Normal& normal = mesh.normal(vertex);
    if (!std::isfinite(normal[0]) || !std::isfinite(normal[1]) || !std::isfinite(normal[2]))
      throw InputError(format(quoted(file), ": vertex ", vertex.idx(), " has a non-finite normal ", describe(normal)));
    const OpenMeshTriMesh::TexCoord2D& uv = mesh.texcoord2D(vertex);
    if (!std::isfinite(uv[0]) || !std::isfinite(uv[1]))
      throw InputError(format(quoted(file), ": vertex ", vertex.idx(), " has a non-finite texture coordinate (",
        uv[0], ", ", uv[1], ")"));
  }


  const std::size_t repeatedCornerTriangles = scan.repeatedCornerTriangles + importer.degenerateTriangles();
  if (importer.facesRead() == 0 && repeatedCornerTriangles == 0)
    throw InputError(format(quoted(file), ": empty mesh (no faces)"));
  return { repeatedCornerTriangles, importer.anyNormalSet(), importer.anyUvSet() };
}

} // namespace

LoadedMesh loadMesh(const std::filesystem::path& file)
{
  OpenMeshTriMesh source;
  const OpenMeshRead read = readWithOpenMesh(file, source);
  LoadedMesh result;
  result.droppedDegenerateTriangles = read.repeatedCornerTriangles;
  const bool fileHasNormals = read.fileHasNormals;
  const bool fileHasUvs = read.fileHasUvs;

  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> compactIndexOf(source.n_vertices(), kUnused);
  std::vector<int> usedSourceVertices;         // compact index -> source vertex index
  std::vector<glm::dvec3> areaWeightedNormals; // per compact vertex
  std::vector<glm::dvec3> firstFaceNormal;     // per compact vertex: fallback when the sum cancels out

  for (const OpenMeshTriMesh::FaceHandle face : source.faces())
  {
    std::array<int, 3> corners{};
    std::size_t cornerCount = 0;
    for (const OpenMeshTriMesh::VertexHandle vertex : source.fv_range(face))
    {
      if (cornerCount < corners.size())
        corners[cornerCount] = vertex.idx();
      ++cornerCount;
    }
    SL_CHECK_MSG(cornerCount == 3, "OpenMesh TriMesh face with ", cornerCount, " corners");

    glm::dvec3 areaNormal{ 0.0 };
    const glm::dvec3 a = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[0])));
    const glm::dvec3 b = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[1])));
    const glm::dvec3 c = toDvec3(source.point(OpenMeshTriMesh::VertexHandle(corners[2])));
    if (isDegenerate(a, b, c, areaNormal))
    {
      ++result.droppedDegenerateTriangles;
      continue;
    }
    for (const int corner : corners)
    {
      std::uint32_t& compact = compactIndexOf[static_cast<std::size_t>(corner)];
      if (compact == kUnused)
      {
        compact = static_cast<std::uint32_t>(usedSourceVertices.size());
        usedSourceVertices.push_back(corner);
        areaWeightedNormals.emplace_back(0.0);
        firstFaceNormal.push_back(glm::normalize(areaNormal));
      }
      areaWeightedNormals[compact] += areaNormal;
      result.mesh.indices.push_back(compact);
    }
  }
  if (result.mesh.indices.empty())
    throw InputError(format("'", file.string(), "': all ", result.droppedDegenerateTriangles,
      " triangles are degenerate (zero area or a repeated corner)"));

  TriangleMesh& mesh = result.mesh;
  mesh.positions.reserve(usedSourceVertices.size());
  mesh.normals.reserve(usedSourceVertices.size());
  for (std::size_t compact = 0; compact < usedSourceVertices.size(); ++compact)
  {
    const OpenMeshTriMesh::VertexHandle vertex(usedSourceVertices[compact]);
    mesh.positions.emplace_back(toDvec3(source.point(vertex)));

    const double smoothLength = glm::length(areaWeightedNormals[compact]);
    glm::dvec3 normal = smoothLength > 0.0 ? areaWeightedNormals[compact] / smoothLength : firstFaceNormal[compact];
    if (fileHasNormals)
    {
      const OpenMeshTriMesh::Normal& fileNormal = source.normal(vertex);
      const glm::dvec3 candidate{ fileNormal[0], fileNormal[1], fileNormal[2] };
      const double length = glm::length(candidate); // finite: the reader refuses non-finite normals
      if (length > 0.0)
        normal = candidate / length;
    }
    mesh.normals.emplace_back(normal);

    if (fileHasUvs)
    {
      const OpenMeshTriMesh::TexCoord2D& uv = source.texcoord2D(vertex);
      mesh.uvs.emplace_back(uv[0], uv[1]);
    }
  }
  return result;
}

} // namespace sl
