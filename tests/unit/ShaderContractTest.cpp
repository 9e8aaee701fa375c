// The contract between a technique's descriptor and its shaders: numbers kept in two languages drift.
// output locations, category codes and shared constants are generated into the shader preamble from the
// descriptor (vtkSLTechniquePass::TechniqueDefines), so a shader may
//  - write only the outputs its descriptor declares, and write every one of them;
//  - use only the category codes and constants the preamble defines (an undefined name in `#if` silently reads
//    0, which is why the preprocessor is run here and not left to the GL);
//  - keep no copy of a generated number (a `const` or `#define` of a generated name, a category code under
//    another name, a budget written as a literal).
//  - read a record shared with C++ (WedgeDrawer.h WedgeRecord, StsvDrawer.h StsvRecord) only through its generated
//    stride and offsets, and keep no copy of any name the preamble defines (also per-frame ones: dcs's counter
//    layers).
// Every technique's fragment shader is assembled as its pass assembles it (sl::assembleShader with the pass's
// preamble) for every combination of its enumeration parameters and shader flag sets, with the pass's other
// shaders (GetPassShaders: wedges, STSVs), preprocessed here (#if / #ifdef / #elif / #else / #endif / #define /
// #undef), and checked; so is the microrect build shader with its claim codes. No GL context is needed.
// A synthetic descriptor and shader, broken one way at a time, show that each check fails when it should.
#include "gl/ShaderLibrary.h"
#include "lightspace/Microrects.h"
#include "passes/FrameResources.h"
#include "structures/microrect/MicrorectStructure.h"
#include "techniques/Registry.h"
#include "techniques/dcs/DcsTechnique.h"
#include "techniques/vtkSLTechniquePass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// ---------------------------------------------------------------------------------------------------------------
// The preamble exactly as the technique's pass builds it. TechniqueDefines(), ParameterDeclarations() and
// GetFragmentShaderPath() are protected members of vtkSLTechniquePass; a pointer to a protected member may be
// formed in a derived class's scope and applied to any vtkSLTechniquePass (C++17 [class.protected]), which is
// how the test reads them without a GL context. The class is never instantiated.
class PreambleAccess : public vtkSLTechniquePass
{
public:
  using PassShader = vtkSLTechniquePass::PassShader;
  static ShaderDefines defines(const vtkSLTechniquePass& pass) { return (pass.*(&PreambleAccess::TechniqueDefines))(); }
  static std::string declarations(const vtkSLTechniquePass& pass)
  {
    return (pass.*(&PreambleAccess::ParameterDeclarations))();
  }
  static std::string fragmentShaderPath(const vtkSLTechniquePass& pass)
  {
    return (pass.*(&PreambleAccess::GetFragmentShaderPath))();
  }
  static std::vector<PassShader> passShaders(const vtkSLTechniquePass& pass)
  {
    return (pass.*(&PreambleAccess::GetPassShaders))();
  }
};

std::string upperCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
  return text;
}

bool startsWith(const std::string& text, const std::string& prefix)
{
  return text.compare(0, prefix.size(), prefix) == 0;
}

bool endsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// ---------------------------------------------------------------------------------------------------------------
// GLSL tokens, enough for the checks: identifiers, numbers (with exponents and suffixes), and operators of one
// or two characters.
struct Token
{
  enum Kind
  {
    Identifier,
    Number,
    Punctuation
  } kind;
  std::string text;
};

bool isIdentifierStart(char c)
{
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}

bool isIdentifierChar(char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

std::vector<Token> tokenize(const std::string& code)
{
  static const std::set<std::string> twoCharacter = { "==", "!=", "<=", ">=", "&&", "||", "++", "--", "+=", "-=",
    "*=", "/=", "<<", ">>", "%=", "&=", "|=", "^=" };
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < code.size())
  {
    const char c = code[i];
    if (std::isspace(static_cast<unsigned char>(c)))
    {
      ++i;
    }
    else if (isIdentifierStart(c))
    {
      std::size_t end = i;
      while (end < code.size() && isIdentifierChar(code[end]))
      {
        ++end;
      }
      tokens.push_back({ Token::Identifier, code.substr(i, end - i) });
      i = end;
    }
    else if (std::isdigit(static_cast<unsigned char>(c)) ||
      (c == '.' && i + 1 < code.size() && std::isdigit(static_cast<unsigned char>(code[i + 1]))))
    {
      std::size_t end = i;
      const bool hex = code.compare(i, 2, "0x") == 0 || code.compare(i, 2, "0X") == 0;
      while (end < code.size())
      {
        const char d = code[end];
        const bool exponentSign = !hex && (d == '-' || d == '+') && (code[end - 1] == 'e' || code[end - 1] == 'E');
        if (!(isIdentifierChar(d) || d == '.' || exponentSign))
        {
          break;
        }
        ++end;
      }
      tokens.push_back({ Token::Number, code.substr(i, end - i) });
      i = end;
    }
    else
    {
      const std::string pair = code.substr(i, 2);
      const std::size_t length = twoCharacter.count(pair) ? 2 : 1;
      tokens.push_back({ Token::Punctuation, code.substr(i, length) });
      i += length;
    }
  }
  return tokens;
}

// The value of an integer-valued literal ("60000", "4.0", "0x10", "3u"), or nullopt.
std::optional<long long> integerLiteral(const std::string& text)
{
  std::string digits = text;
  const bool hex = startsWith(digits, "0x") || startsWith(digits, "0X");
  while (!digits.empty() && !hex && std::isalpha(static_cast<unsigned char>(digits.back())) &&
    digits.back() != 'e' && digits.back() != 'E')
  {
    digits.pop_back(); // u, f, lf suffixes
  }
  if (hex)
  {
    while (!digits.empty() && (digits.back() == 'u' || digits.back() == 'U'))
    {
      digits.pop_back();
    }
    return std::strtoll(digits.c_str(), nullptr, 16);
  }
  char* end = nullptr;
  const double value = std::strtod(digits.c_str(), &end);
  if (end == digits.c_str() || *end != '\0' || !(std::abs(value) < 9e18) ||
    value != static_cast<double>(static_cast<long long>(value)))
  {
    return std::nullopt;
  }
  return static_cast<long long>(value);
}

// Removes // and /* */ comments, keeping line breaks (directives stay one a line).
std::string stripComments(const std::string& source)
{
  std::string out;
  out.reserve(source.size());
  std::size_t i = 0;
  while (i < source.size())
  {
    if (source.compare(i, 2, "//") == 0)
    {
      while (i < source.size() && source[i] != '\n')
      {
        ++i;
      }
    }
    else if (source.compare(i, 2, "/*") == 0)
    {
      const std::size_t end = source.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? source.size() : end + 2;
      for (std::size_t k = i; k < stop; ++k)
      {
        if (source[k] == '\n')
        {
          out += '\n';
        }
      }
      i = stop;
    }
    else
    {
      out += source[i++];
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// The GLSL preprocessor, as far as the shaders use it: object- and function-like #define (recorded, expanded
// only inside #if), #undef, #if / #ifdef / #ifndef / #elif / #else / #endif with defined(), integer arithmetic,
// comparisons and logic. An identifier that is not a macro inside #if is an error here (C's rule, reading 0,
// is exactly the silent mistake the test exists to catch).
struct Preprocessed
{
  std::string activeCode; // the lines that survive, directives removed
  std::map<std::string, std::string> macros; // object-like: body; function-like: "(...)"
  std::vector<std::string> bodyDefinitions;  // names #defined by the shader files (not by the preamble)
  std::vector<std::string> errors;
};

class ConditionEvaluator
{
public:
  ConditionEvaluator(const std::map<std::string, std::string>& macros, std::vector<std::string>& errors, int depth = 0)
    : macros_(macros)
    , errors_(errors)
    , depth_(depth)
  {
  }

  long long evaluate(const std::string& expression)
  {
    tokens_ = tokenize(expression);
    position_ = 0;
    const long long value = logicalOr();
    if (position_ != tokens_.size())
    {
      errors_.push_back("cannot parse '" + expression + "' in a preprocessor condition");
    }
    return value;
  }

private:
  bool accept(const std::string& text)
  {
    if (position_ < tokens_.size() && tokens_[position_].kind == Token::Punctuation && tokens_[position_].text == text)
    {
      ++position_;
      return true;
    }
    return false;
  }

  long long logicalOr()
  {
    long long value = logicalAnd();
    while (accept("||"))
    {
      const long long right = logicalAnd();
      value = (value || right) ? 1 : 0;
    }
    return value;
  }

  long long logicalAnd()
  {
    long long value = equality();
    while (accept("&&"))
    {
      const long long right = equality();
      value = (value && right) ? 1 : 0;
    }
    return value;
  }

  long long equality()
  {
    long long value = relational();
    while (true)
    {
      if (accept("=="))
      {
        value = value == relational() ? 1 : 0;
      }
      else if (accept("!="))
      {
        value = value != relational() ? 1 : 0;
      }
      else
      {
        return value;
      }
    }
  }

  long long relational()
  {
    long long value = additive();
    while (true)
    {
      if (accept("<="))
      {
        value = value <= additive() ? 1 : 0;
      }
      else if (accept(">="))
      {
        value = value >= additive() ? 1 : 0;
      }
      else if (accept("<"))
      {
        value = value < additive() ? 1 : 0;
      }
      else if (accept(">"))
      {
        value = value > additive() ? 1 : 0;
      }
      else
      {
        return value;
      }
    }
  }

  long long additive()
  {
    long long value = multiplicative();
    while (true)
    {
      if (accept("+"))
      {
        value += multiplicative();
      }
      else if (accept("-"))
      {
        value -= multiplicative();
      }
      else
      {
        return value;
      }
    }
  }

  long long multiplicative()
  {
    long long value = unary();
    while (true)
    {
      if (accept("*"))
      {
        value *= unary();
      }
      else if (accept("/") || accept("%"))
      {
        const bool modulo = tokens_[position_ - 1].text == "%";
        const long long divisor = unary();
        if (divisor == 0)
        {
          errors_.push_back("division by zero in a preprocessor condition");
          return 0;
        }
        value = modulo ? value % divisor : value / divisor;
      }
      else
      {
        return value;
      }
    }
  }

  long long unary()
  {
    if (accept("!"))
    {
      return unary() ? 0 : 1;
    }
    if (accept("-"))
    {
      return -unary();
    }
    if (accept("+"))
    {
      return unary();
    }
    return primary();
  }

  long long primary()
  {
    if (accept("("))
    {
      const long long value = logicalOr();
      if (!accept(")"))
      {
        errors_.push_back("unbalanced parentheses in a preprocessor condition");
      }
      return value;
    }
    if (position_ >= tokens_.size())
    {
      errors_.push_back("a preprocessor condition ends early");
      return 0;
    }
    const Token token = tokens_[position_++];
    if (token.kind == Token::Number)
    {
      const std::optional<long long> value = integerLiteral(token.text);
      if (!value)
      {
        errors_.push_back("'" + token.text + "' is not an integer in a preprocessor condition");
      }
      return value.value_or(0);
    }
    if (token.kind != Token::Identifier)
    {
      errors_.push_back("unexpected '" + token.text + "' in a preprocessor condition");
      return 0;
    }
    if (token.text == "defined")
    {
      const bool parenthesised = accept("(");
      if (position_ >= tokens_.size() || tokens_[position_].kind != Token::Identifier)
      {
        errors_.push_back("defined without a name");
        return 0;
      }
      const bool defined = macros_.count(tokens_[position_++].text) != 0;
      if (parenthesised && !accept(")"))
      {
        errors_.push_back("defined( without )");
      }
      return defined ? 1 : 0;
    }
    const auto macro = macros_.find(token.text);
    if (macro == macros_.end())
    {
      errors_.push_back(token.text + " is used in a preprocessor condition but defined nowhere (it would read 0)");
      return 0;
    }
    if (macro->second.empty() || depth_ > 32)
    {
      errors_.push_back(token.text + " has no value to compare in a preprocessor condition");
      return 0;
    }
    ConditionEvaluator inner(macros_, errors_, depth_ + 1);
    return inner.evaluate(macro->second);
  }

  const std::map<std::string, std::string>& macros_;
  std::vector<std::string>& errors_;
  int depth_;
  std::vector<Token> tokens_;
  std::size_t position_ = 0;
};

std::string trim(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos)
  {
    return {};
  }
  const std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// `preamble`: the generated defines, which the source's first #define lines are.
Preprocessed preprocess(const std::string& source, const ShaderDefines& preamble)
{
  std::map<std::string, std::string> preambleValues(preamble.begin(), preamble.end());
  std::set<std::string> preambleSeen;
  Preprocessed result;
  struct Branch
  {
    bool parentActive;
    bool taken;  // some branch of this #if has been active
    bool active; // the current branch
  };
  std::vector<Branch> stack;
  const auto active = [&] { return stack.empty() || stack.back().active; };
  std::istringstream lines(stripComments(source));
  std::string line;
  while (std::getline(lines, line))
  {
    const std::string text = trim(line);
    if (text.empty() || text[0] != '#')
    {
      if (active())
      {
        result.activeCode += line;
        result.activeCode += '\n';
      }
      continue;
    }
    std::size_t start = 1;
    while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start])))
    {
      ++start;
    }
    std::size_t end = start;
    while (end < text.size() && isIdentifierChar(text[end]))
    {
      ++end;
    }
    const std::string directive = text.substr(start, end - start);
    const std::string argument = trim(text.substr(end));
    const auto evaluate = [&](const std::string& expression) {
      ConditionEvaluator evaluator(result.macros, result.errors);
      return evaluator.evaluate(expression) != 0;
    };
    if (directive == "if" || directive == "ifdef" || directive == "ifndef")
    {
      const bool parentActive = active();
      bool condition = false;
      if (parentActive)
      {
        condition = directive == "if" ? evaluate(argument)
          : directive == "ifdef"       ? result.macros.count(argument) != 0
                                       : result.macros.count(argument) == 0;
      }
      stack.push_back({ parentActive, condition, parentActive && condition });
    }
    else if (directive == "elif" || directive == "else")
    {
      if (stack.empty())
      {
        result.errors.push_back("#" + directive + " without #if");
        continue;
      }
      Branch& branch = stack.back();
      const bool condition =
        branch.parentActive && !branch.taken && (directive == "else" || evaluate(argument));
      branch.active = condition;
      branch.taken = branch.taken || condition;
    }
    else if (directive == "endif")
    {
      if (stack.empty())
      {
        result.errors.push_back("#endif without #if");
        continue;
      }
      stack.pop_back();
    }
    else if (!active())
    {
      continue;
    }
    else if (directive == "define")
    {
      std::size_t nameEnd = 0;
      while (nameEnd < argument.size() && isIdentifierChar(argument[nameEnd]))
      {
        ++nameEnd;
      }
      const std::string name = argument.substr(0, nameEnd);
      const bool functionLike = nameEnd < argument.size() && argument[nameEnd] == '(';
      const std::string body = functionLike ? "(...)" : trim(argument.substr(nameEnd));
      const auto generated = preambleValues.find(name);
      if (generated != preambleValues.end() && !preambleSeen.count(name) && generated->second == body)
      {
        preambleSeen.insert(name); // the preamble's own line
      }
      else
      {
        result.bodyDefinitions.push_back(name);
        const auto previous = result.macros.find(name);
        if (previous != result.macros.end() && previous->second != body)
        {
          result.errors.push_back(name + " is #defined again with another value (" + previous->second + " -> " + body + ")");
        }
      }
      result.macros[name] = body;
    }
    else if (directive == "undef")
    {
      result.macros.erase(argument);
    }
    else if (directive == "error")
    {
      result.errors.push_back("#error " + argument);
    }
    // #version, #extension, #pragma, #line: nothing to check.
  }
  if (!stack.empty())
  {
    result.errors.push_back("#if without #endif");
  }
  return result;
}

// ---------------------------------------------------------------------------------------------------------------
// The contract. Returns one line per violation; empty when the shader keeps it.

// An output declaration: `layout(... OUT_X ...) out float name;` or `layout(r32f, binding = OUT_X) uniform
// writeonly image2D name;`.
struct OutputBinding
{
  std::string variable;
  bool image = false;
};

// `checkOutputs`: the technique's own fragment shader, which writes the descriptor's outputs (false for the other
// shaders a pass or a structure's build assembles, which write targets of their own).
std::vector<std::string> contractViolations(const TechniqueDescriptor& descriptor, const ShaderDefines& preamble,
  const std::string& assembledSource, bool checkOutputs = true)
{
  std::vector<std::string> violations;
  const Preprocessed shader = preprocess(assembledSource, preamble);
  for (const std::string& error : shader.errors)
  {
    violations.push_back("preprocessor: " + error);
  }
  const std::vector<Token> tokens = tokenize(shader.activeCode);

  // What the descriptor generates.
  std::set<std::string> outputs{ "OUT_VISIBILITY" };
  for (const BufferSpec& buffer : descriptor.buffers)
  {
    if (!buffer.fromPass) // read back by the pass itself, no output location
    {
      outputs.insert("OUT_" + upperCase(buffer.name));
    }
  }
  std::map<std::string, int> categoryCodes; // CLASSIFICATION_LIT -> 1
  std::vector<std::string> categoryPrefixes;
  for (const BufferSpec& buffer : descriptor.buffers)
  {
    if (buffer.kind != BufferKind::Categorical)
    {
      continue;
    }
    categoryPrefixes.push_back(upperCase(buffer.name) + "_");
    for (std::size_t code = 0; code < buffer.categoryIdentifiers.size(); ++code)
    {
      const std::string name = upperCase(buffer.name + "_" + buffer.categoryIdentifiers[code]);
      categoryCodes[name] = static_cast<int>(code);
    }
  }
  std::set<std::string> generated(outputs.begin(), outputs.end());
  // Every name the preamble defines is generated, also those a pass computes per frame (dcs's counter layers from
  // the sample count, GetExtraDefines) and a structure's (LIGHT_SAMPLE_COUNT): a shader keeps no copy of any.
  for (const auto& [name, value] : preamble)
  {
    generated.insert(name);
  }
  for (const auto& [name, code] : categoryCodes)
  {
    generated.insert(name);
  }
  for (const ShaderConstant& constant : descriptor.shaderConstants)
  {
    generated.insert(constant.name);
  }
  for (const ParameterSpec& spec : descriptor.parameters)
  {
    if (!spec.choices.empty())
    {
      generated.insert(upperCase(spec.name));
      for (const std::string& choice : spec.choices)
      {
        generated.insert(upperCase(spec.name + "_" + choice));
      }
    }
  }

  // `const` declarations of the active code: name, and the value when the initializer is one literal.
  std::map<std::string, std::optional<long long>> constants;
  for (std::size_t i = 0; i + 2 < tokens.size(); ++i)
  {
    if (tokens[i].kind != Token::Identifier || tokens[i].text != "const")
    {
      continue;
    }
    std::size_t k = i + 1;
    std::string name;
    while (k < tokens.size() && tokens[k].kind == Token::Identifier)
    {
      name = tokens[k++].text;
    }
    if (name.empty() || k - i < 3)
    {
      continue; // `const` followed by a type only: a parameter or a cast, not a declaration of a name
    }
    std::optional<long long> value;
    if (k + 2 < tokens.size() && tokens[k].text == "=" && tokens[k + 1].kind == Token::Number && tokens[k + 2].text == ";")
    {
      value = integerLiteral(tokens[k + 1].text);
    }
    constants[name] = value;
  }

  // 1. Hand copies of generated names: a `const` or a `#define` in the shader files.
  for (const auto& [name, value] : constants)
  {
    if (generated.count(name))
    {
      violations.push_back("declares const " + name + ", which the descriptor generates: a hand-copied number");
    }
  }
  for (const std::string& name : shader.bodyDefinitions)
  {
    if (generated.count(name))
    {
      violations.push_back("#defines " + name + ", which the descriptor generates: a hand-copied number");
    }
  }
  // A category code under another name: a const ending in a category's identifier, with its code.
  for (const auto& [name, value] : constants)
  {
    for (const BufferSpec& buffer : descriptor.buffers)
    {
      for (std::size_t code = 0; code < buffer.categoryIdentifiers.size(); ++code)
      {
        const std::string identifier = buffer.categoryIdentifiers[code];
        if (value && *value == static_cast<long long>(code) && !generated.count(name) &&
          (name == identifier || endsWith(name, "_" + identifier)))
        {
          violations.push_back("const " + name + " = " + std::to_string(*value) + " copies the code of `" + buffer.name +
            "` category " + identifier + " (use " + upperCase(buffer.name + "_" + identifier) + ")");
        }
      }
    }
  }
  // A shared constant written as a literal. Integers below 100 are too common in shader arithmetic to be told
  // from copies; the name checks above cover those.
  for (const Token& token : tokens)
  {
    if (token.kind != Token::Number)
    {
      continue;
    }
    const std::optional<long long> value = integerLiteral(token.text);
    for (const ShaderConstant& constant : descriptor.shaderConstants)
    {
      if (value && *value == constant.value && constant.value >= 100)
      {
        violations.push_back("the literal " + token.text + " copies " + constant.name + " (" + constant.doc + ")");
      }
    }
  }

  // Records shared with C++ (a storage buffer of vec4 records: WedgeDrawer.h WedgeRecord, StsvDrawer.h StsvRecord):
  // a generated stride <RECORD>_VEC4 and field offsets <RECORD>_<FIELD>. A const or #define of the shader's own under
  // a record's prefix is a copy of its layout; an array indexed with a record's stride anywhere is a record array,
  // and every subscript of it must name a stride and hold no literal offset; a function reading such an array (an
  // accessor, `wedgeRecordVec4(wedge, field)`) takes no literal offset either.
  std::vector<std::string> recordPrefixes;
  for (const std::string& name : generated)
  {
    if (endsWith(name, "_VEC4"))
    {
      recordPrefixes.push_back(name.substr(0, name.size() - std::string("_VEC4").size()));
    }
  }
  const auto recordPrefixOf = [&](const std::string& name) -> std::string {
    for (const std::string& prefix : recordPrefixes)
    {
      if (name == prefix || startsWith(name, prefix + "_"))
      {
        return prefix;
      }
    }
    return {};
  };
  const auto isStride = [&](const std::string& name) {
    return endsWith(name, "_VEC4") && std::find(recordPrefixes.begin(), recordPrefixes.end(),
      name.substr(0, name.size() - std::string("_VEC4").size())) != recordPrefixes.end();
  };
  std::vector<std::string> ownNames;
  for (const auto& [name, value] : constants)
  {
    ownNames.push_back(name);
  }
  ownNames.insert(ownNames.end(), shader.bodyDefinitions.begin(), shader.bodyDefinitions.end());
  for (const std::string& name : ownNames)
  {
    const std::string prefix = recordPrefixOf(name);
    if (!prefix.empty() && !generated.count(name))
    {
      violations.push_back("declares " + name + ", a copy of the layout of record " + prefix +
        " (use its generated " + prefix + "_VEC4 and " + prefix + "_<FIELD>)");
    }
  }
  // The closing bracket or parenthesis matching the one at `open`.
  const auto closing = [&](std::size_t open) {
    const std::string opener = tokens[open].text;
    const std::string closer = opener == "[" ? "]" : ")";
    int depth = 0;
    for (std::size_t k = open; k < tokens.size(); ++k)
    {
      depth += tokens[k].text == opener ? 1 : tokens[k].text == closer ? -1 : 0;
      if (depth == 0)
      {
        return k;
      }
    }
    return tokens.size();
  };
  std::set<std::string> recordArrays;
  for (std::size_t i = 0; i + 1 < tokens.size(); ++i)
  {
    if (tokens[i].kind == Token::Identifier && tokens[i + 1].text == "[")
    {
      const std::size_t end = closing(i + 1);
      for (std::size_t k = i + 2; k < end; ++k)
      {
        if (isStride(tokens[k].text))
        {
          recordArrays.insert(tokens[i].text);
        }
      }
    }
  }
  // Accessors: functions (`type name(...) {`) whose body subscripts a record array.
  std::set<std::string> accessors;
  std::set<std::size_t> accessorDefinitions; // token index of each accessor's name in its definition
  for (std::size_t i = 0; i + 2 < tokens.size(); ++i)
  {
    static const std::set<std::string> notFunctions = { "if", "while", "for", "switch", "return", "else" };
    if (tokens[i].kind != Token::Identifier || tokens[i + 1].kind != Token::Identifier || tokens[i + 2].text != "(" ||
      notFunctions.count(tokens[i].text) || notFunctions.count(tokens[i + 1].text))
    {
      continue;
    }
    const std::size_t parameters = closing(i + 2);
    if (parameters + 1 >= tokens.size() || tokens[parameters + 1].text != "{")
    {
      continue;
    }
    int depth = 0;
    for (std::size_t k = parameters + 1; k < tokens.size(); ++k)
    {
      depth += tokens[k].text == "{" ? 1 : tokens[k].text == "}" ? -1 : 0;
      if (depth == 0)
      {
        break;
      }
      if (recordArrays.count(tokens[k].text) && k + 1 < tokens.size() && tokens[k + 1].text == "[")
      {
        accessors.insert(tokens[i + 1].text);
        accessorDefinitions.insert(i + 1);
      }
    }
  }
  for (std::size_t i = 0; i + 1 < tokens.size(); ++i)
  {
    const bool subscript = recordArrays.count(tokens[i].text) && tokens[i + 1].text == "[";
    const bool call = accessors.count(tokens[i].text) && tokens[i + 1].text == "(" && !accessorDefinitions.count(i);
    if (!subscript && !call)
    {
      continue;
    }
    const std::size_t end = closing(i + 1);
    if (subscript && end == i + 2)
    {
      continue; // the declaration of a runtime-sized array, `vec4 wedgeData[];`
    }
    std::string text;
    bool namesStride = false;
    std::string literal;
    for (std::size_t k = i + 2; k < end; ++k)
    {
      text += (text.empty() ? "" : " ") + tokens[k].text;
      namesStride = namesStride || isStride(tokens[k].text);
      if (tokens[k].kind == Token::Number && literal.empty())
      {
        literal = tokens[k].text;
      }
    }
    const std::string access = tokens[i].text + (subscript ? "[" : "(") + text + (subscript ? "]" : ")");
    if (!literal.empty())
    {
      violations.push_back("reads a record as " + access + " with the literal " + literal +
        ": a hand-copied stride or offset (use the record's generated names)");
    }
    else if (subscript && !namesStride)
    {
      violations.push_back("reads a record as " + access + " without its generated stride (<RECORD>_VEC4)");
    }
  }

  // 2. Names used: outputs and category codes the descriptor declares; every upper-case name defined somewhere.
  std::set<std::string> reported;
  for (const Token& token : tokens)
  {
    if (token.kind != Token::Identifier || reported.count(token.text))
    {
      continue;
    }
    const std::string& name = token.text;
    if (startsWith(name, "OUT_") && !outputs.count(name))
    {
      violations.push_back("uses " + name + ", an output the descriptor does not declare");
      reported.insert(name);
      continue;
    }
    const bool categoryLike = std::any_of(categoryPrefixes.begin(), categoryPrefixes.end(),
      [&](const std::string& prefix) { return startsWith(name, prefix); });
    if (categoryLike && !categoryCodes.count(name) && !startsWith(name, "OUT_"))
    {
      violations.push_back("uses " + name + ", a category code the descriptor does not declare");
      reported.insert(name);
      continue;
    }
    const bool upper = std::all_of(name.begin(), name.end(),
      [](char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; });
    const bool builtIn = startsWith(name, "GL_") || startsWith(name, "__");
    if (upper && name.size() > 1 && !builtIn && !shader.macros.count(name) && !constants.count(name) &&
      std::find(shader.bodyDefinitions.begin(), shader.bodyDefinitions.end(), name) == shader.bodyDefinitions.end())
    {
      violations.push_back("uses " + name + ", which neither the descriptor nor the shader declares");
      reported.insert(name);
    }
  }

  if (!checkOutputs)
  {
    return violations;
  }
  // 3. Every output bound to a variable, and that variable written (assigned, or image-stored).
  std::map<std::string, OutputBinding> bindings; // OUT_X -> variable
  for (std::size_t i = 0; i < tokens.size(); ++i)
  {
    if (tokens[i].text != "layout" || i + 1 >= tokens.size() || tokens[i + 1].text != "(")
    {
      continue;
    }
    std::size_t k = i + 2;
    std::vector<std::string> locations;
    while (k < tokens.size() && tokens[k].text != ")")
    {
      if (startsWith(tokens[k].text, "OUT_"))
      {
        locations.push_back(tokens[k].text);
      }
      ++k;
    }
    OutputBinding binding;
    for (++k; k < tokens.size() && tokens[k].text != ";"; ++k)
    {
      if (tokens[k].kind == Token::Identifier)
      {
        binding.image = binding.image || startsWith(tokens[k].text, "image");
        binding.variable = tokens[k].text;
      }
    }
    for (const std::string& location : locations)
    {
      bindings[location] = binding;
    }
  }
  for (const std::string& output : outputs)
  {
    const auto binding = bindings.find(output);
    if (binding == bindings.end())
    {
      violations.push_back("never binds " + output + ", an output the descriptor declares");
      continue;
    }
    const std::string& variable = binding->second.variable;
    bool written = false;
    for (std::size_t i = 0; i + 2 < tokens.size() && !written; ++i)
    {
      if (binding->second.image)
      {
        written = tokens[i].text == "imageStore" && tokens[i + 1].text == "(" && tokens[i + 2].text == variable;
        continue;
      }
      if (tokens[i].text != variable)
      {
        continue;
      }
      std::size_t k = i + 1;
      if (tokens[k].text == "[") // an element
      {
        while (k < tokens.size() && tokens[k].text != "]")
        {
          ++k;
        }
        ++k;
      }
      if (k + 1 < tokens.size() && tokens[k].text == ".") // a swizzle
      {
        k += 2;
      }
      static const std::set<std::string> assignments = { "=", "+=", "-=", "*=", "/=" };
      written = k < tokens.size() && assignments.count(tokens[k].text) != 0;
    }
    if (!written)
    {
      violations.push_back("never writes " + variable + " (" + output + "), an output the descriptor declares");
    }
  }
  return violations;
}

std::string joined(const std::vector<std::string>& lines)
{
  std::string text;
  for (const std::string& line : lines)
  {
    text += "\n  " + line;
  }
  return text;
}

bool mentions(const std::vector<std::string>& violations, const std::string& word)
{
  return std::any_of(violations.begin(), violations.end(),
    [&](const std::string& violation) { return violation.find(word) != std::string::npos; });
}

// ---------------------------------------------------------------------------------------------------------------
// A synthetic technique, to show each check failing. Its preamble comes from a real pass (`hard`'s, which adds
// no defines of its own) pointed at the synthetic descriptor.
TechniqueDescriptor syntheticDescriptor()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "synthetic";
  descriptor.parameters = { { "filter", 0, 0, 1, "", "a two-way variant", { "box", "tent" }, true } };
  descriptor.buffers = {
    { "kernel_texels", "texels", "a continuous buffer" },
    { "classification", "", "a categorical buffer", BufferKind::Categorical, { "not tested", "lit", "over the loop budget" },
      SubLightCombine::First, { "NOT_TESTED", "LIT", "OVER_BUDGET" } },
  };
  descriptor.shaderConstants = { { "LOOP_BUDGET", 60000, "iterations past which a pixel is flagged" },
    { "SAMPLE_RECORD_VEC4", 3, "vec4s per record (a synthetic record)" },
    { "SAMPLE_RECORD_CENTRE", 1, "a record's centre" } };
  return descriptor;
}

const char* const syntheticShader = R"(
layout(location = OUT_VISIBILITY) out float outVisibility;
layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;
layout(location = OUT_CLASSIFICATION) out float outClassification;
layout(std430, binding = 0) readonly buffer Records
{
  vec4 recordData[];
};
vec4 recordVec4(int record, int field)
{
  return recordData[SAMPLE_RECORD_VEC4 * record + field];
}
void main()
{
  int iterations = int(gl_FragCoord.x);
  outVisibility = 1.0;
  outVisibility *= recordVec4(iterations, SAMPLE_RECORD_CENTRE).x;
  outKernelTexels = 0.0;
#if FILTER == FILTER_TENT
  outKernelTexels = 2.0;
#endif
  outClassification = iterations > LOOP_BUDGET ? CLASSIFICATION_OVER_BUDGET : CLASSIFICATION_LIT;
}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos)
  {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The violations of `body` for each choice of `filter`.
std::vector<std::vector<std::string>> syntheticViolations(const std::string& body)
{
  static const TechniqueDescriptor descriptor = syntheticDescriptor();
  const vtkSmartPointer<vtkSLTechniquePass> pass = findTechnique("hard").createPass();
  FrameResources frame;
  frame.technique = &descriptor;
  frame.parameters = descriptor.defaultParameters();
  pass->SetFrame(&frame);
  std::vector<std::vector<std::string>> perChoice;
  for (const std::string& choice : descriptor.parameters[0].choices)
  {
    frame.parameters.set("filter=" + choice);
    const ShaderDefines defines = PreambleAccess::defines(*pass);
    std::string source = "#version 450 core\n";
    for (const auto& [name, value] : defines)
    {
      source += "#define " + name + (value.empty() ? "" : " ") + value + "\n";
    }
    perChoice.push_back(contractViolations(descriptor, defines, source + body));
  }
  return perChoice;
}

TEST(ShaderContract, TheSyntheticShaderKeepsItsDescriptorsContract)
{
  for (const std::vector<std::string>& violations : syntheticViolations(syntheticShader))
  {
    EXPECT_TRUE(violations.empty()) << joined(violations);
  }
}

TEST(ShaderContract, AnOutputTheDescriptorDoesNotDeclareFails)
{
  const std::string body = replaced(syntheticShader, "void main()\n{",
    "layout(location = OUT_STRAY) out float outStray;\nvoid main()\n{\n  outStray = 0.0;");
  for (const std::vector<std::string>& violations : syntheticViolations(body))
  {
    EXPECT_TRUE(mentions(violations, "uses OUT_STRAY, an output the descriptor does not declare")) << joined(violations);
  }
}

TEST(ShaderContract, AnOutputNeverWrittenFailsInTheVariantsThatMissIt)
{
  // Written only when FILTER == FILTER_TENT: the box variant fails, the tent variant passes.
  const std::vector<std::vector<std::string>> violations =
    syntheticViolations(replaced(syntheticShader, "  outKernelTexels = 0.0;\n", ""));
  ASSERT_EQ(violations.size(), 2u);
  EXPECT_TRUE(mentions(violations[0], "never writes outKernelTexels (OUT_KERNEL_TEXELS)")) << joined(violations[0]);
  EXPECT_TRUE(violations[1].empty()) << joined(violations[1]);
  // Not bound at all.
  const std::string unbound = replaced(syntheticShader,
    "layout(location = OUT_KERNEL_TEXELS) out float outKernelTexels;\n", "float outKernelTexels;\n");
  for (const std::vector<std::string>& perChoice : syntheticViolations(unbound))
  {
    EXPECT_TRUE(mentions(perChoice, "never binds OUT_KERNEL_TEXELS")) << joined(perChoice);
  }
}

TEST(ShaderContract, ACategoryCodeTheDescriptorDoesNotDeclareFails)
{
  const std::string body = replaced(syntheticShader, "CLASSIFICATION_LIT;", "CLASSIFICATION_UMBRA;");
  for (const std::vector<std::string>& violations : syntheticViolations(body))
  {
    EXPECT_TRUE(mentions(violations, "uses CLASSIFICATION_UMBRA, a category code the descriptor does not declare"))
      << joined(violations);
  }
}

TEST(ShaderContract, AConstantNobodyDeclaresFails)
{
  const std::string body = replaced(syntheticShader, "outVisibility = 1.0;", "outVisibility = float(MAX_TAPS);");
  for (const std::vector<std::string>& violations : syntheticViolations(body))
  {
    EXPECT_TRUE(mentions(violations, "uses MAX_TAPS, which neither the descriptor nor the shader declares")) << joined(violations);
  }
  // In a condition, an undefined name would silently read 0: FILTER_GAUSS == FILTER_BOX there.
  const std::string condition = replaced(syntheticShader, "#if FILTER == FILTER_TENT", "#if FILTER == FILTER_GAUSS");
  for (const std::vector<std::string>& violations : syntheticViolations(condition))
  {
    EXPECT_TRUE(mentions(violations, "FILTER_GAUSS is used in a preprocessor condition but defined nowhere")) << joined(violations);
  }
}

TEST(ShaderContract, HandCopiedNumbersFail)
{
  // The generated name declared again (the old way: a const beside the C++ constexpr).
  const std::string redeclared = replaced(syntheticShader, "void main()", "const int LOOP_BUDGET = 60000;\nvoid main()");
  for (const std::vector<std::string>& violations : syntheticViolations(redeclared))
  {
    EXPECT_TRUE(mentions(violations, "declares const LOOP_BUDGET, which the descriptor generates")) << joined(violations);
  }
  const std::string redefined = replaced(syntheticShader, "void main()", "#define CLASSIFICATION_LIT 1\nvoid main()");
  for (const std::vector<std::string>& violations : syntheticViolations(redefined))
  {
    EXPECT_TRUE(mentions(violations, "#defines CLASSIFICATION_LIT, which the descriptor generates")) << joined(violations);
  }
  // A category code under a name of the shader's own.
  const std::string renamed = replaced(replaced(syntheticShader, "void main()", "const float CLASS_LIT = 1.0;\nvoid main()"),
    ": CLASSIFICATION_LIT;", ": CLASS_LIT;");
  for (const std::vector<std::string>& violations : syntheticViolations(renamed))
  {
    EXPECT_TRUE(mentions(violations, "const CLASS_LIT = 1 copies the code of `classification` category LIT")) << joined(violations);
  }
  // The budget as a literal.
  const std::string literal = replaced(syntheticShader, "iterations > LOOP_BUDGET", "iterations > 60000");
  for (const std::vector<std::string>& violations : syntheticViolations(literal))
  {
    EXPECT_TRUE(mentions(violations, "the literal 60000 copies LOOP_BUDGET")) << joined(violations);
  }
}

TEST(ShaderContract, HandCopiedRecordLayoutsFail)
{
  // The record read at a literal offset, directly or through its accessor.
  const std::string direct =
    replaced(syntheticShader, "recordVec4(iterations, SAMPLE_RECORD_CENTRE)", "recordData[3 * iterations + 1]");
  for (const std::vector<std::string>& violations : syntheticViolations(direct))
  {
    EXPECT_TRUE(mentions(violations, "reads a record as recordData[3 * iterations + 1] with the literal 3")) << joined(violations);
  }
  const std::string unnamed = replaced(syntheticShader, "recordVec4(iterations, SAMPLE_RECORD_CENTRE)", "recordData[iterations]");
  for (const std::vector<std::string>& violations : syntheticViolations(unnamed))
  {
    EXPECT_TRUE(mentions(violations, "reads a record as recordData[iterations] without its generated stride")) << joined(violations);
  }
  const std::string accessor = replaced(syntheticShader, "recordVec4(iterations, SAMPLE_RECORD_CENTRE)", "recordVec4(iterations, 1)");
  for (const std::vector<std::string>& violations : syntheticViolations(accessor))
  {
    EXPECT_TRUE(mentions(violations, "reads a record as recordVec4(iterations , 1) with the literal 1")) << joined(violations);
  }
  // The stride or an offset kept under a name of the shader's own (the old `const int STSV_RECORD = 11;`).
  const std::string stride = replaced(replaced(syntheticShader, "void main()", "const int SAMPLE_RECORD = 3;\nvoid main()"),
    "SAMPLE_RECORD_VEC4 * record", "SAMPLE_RECORD * record");
  for (const std::vector<std::string>& violations : syntheticViolations(stride))
  {
    EXPECT_TRUE(mentions(violations, "declares SAMPLE_RECORD, a copy of the layout of record SAMPLE_RECORD")) << joined(violations);
  }
  const std::string offset = replaced(syntheticShader, "void main()", "#define SAMPLE_RECORD_RADIUS 2\nvoid main()");
  for (const std::vector<std::string>& violations : syntheticViolations(offset))
  {
    EXPECT_TRUE(mentions(violations, "declares SAMPLE_RECORD_RADIUS, a copy of the layout of record SAMPLE_RECORD")) << joined(violations);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Every registered technique.

// Every combination of the enumeration parameters' choices, as `name=choice` assignments.
std::vector<std::vector<std::string>> enumerationCombinations(const TechniqueDescriptor& descriptor)
{
  std::vector<std::vector<std::string>> combinations = { {} };
  for (const ParameterSpec& spec : descriptor.parameters)
  {
    if (spec.choices.empty())
    {
      continue;
    }
    std::vector<std::vector<std::string>> extended;
    for (const std::vector<std::string>& combination : combinations)
    {
      for (const std::string& choice : spec.choices)
      {
        extended.push_back(combination);
        extended.back().push_back(spec.name + "=" + choice);
      }
    }
    combinations = std::move(extended);
  }
  return combinations;
}

// Whether `token` occurs as a whole identifier in `source`.
bool mentionsIdentifier(const std::string& source, const std::string& token)
{
  const auto isIdentifier = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = source.find(token); at != std::string::npos; at = source.find(token, at + 1))
  {
    const bool startsWord = at == 0 || !isIdentifier(source[at - 1]);
    const bool endsWord = at + token.size() >= source.size() || !isIdentifier(source[at + token.size()]);
    if (startsWord && endsWord)
    {
      return true;
    }
  }
  return false;
}

// The enumeration parameters whose choice can change one of the technique's programs: its shaders (without the
// preamble) name the parameter's define or one of its choices' defines, or another choice changes a define the
// preamble gives besides the parameter's own (a light-space structure's, e.g. the shadow map's depth_layer). The
// others (e.g. caster_faces and depth_layer's midpoint and dual, read only by the shadow map's own build) reach a
// program only as #define lines nothing tests, so every combination of them compiles to the same program.
std::vector<std::vector<std::string>> shaderRelevantCombinations(
  const TechniqueDescriptor& descriptor, const vtkSLTechniquePass& pass, FrameResources& frame)
{
  std::string sources = assembleShader(PreambleAccess::fragmentShaderPath(pass), {}, "");
  for (const PreambleAccess::PassShader& shader : PreambleAccess::passShaders(pass))
  {
    sources += assembleShader(shader.path, {}, "");
  }
  TechniqueDescriptor relevant = descriptor;
  relevant.parameters.clear();
  for (const ParameterSpec& spec : descriptor.parameters)
  {
    bool reaches = spec.choices.empty() || mentionsIdentifier(sources, upperCase(spec.name));
    const std::string ownPrefix = upperCase(spec.name);
    std::vector<ShaderDefines> others;
    for (const std::string& choice : spec.choices)
    {
      reaches = reaches || mentionsIdentifier(sources, upperCase(spec.name + "_" + choice));
      frame.parameters = descriptor.defaultParameters();
      frame.parameters.set(spec.name + "=" + choice);
      ShaderDefines defines;
      for (const auto& define : PreambleAccess::defines(pass))
      {
        if (!startsWith(define.first, ownPrefix))
        {
          defines.push_back(define);
        }
      }
      reaches = reaches || (!others.empty() && defines != others.front());
      others.push_back(defines);
    }
    if (reaches)
    {
      relevant.parameters.push_back(spec);
    }
  }
  return enumerationCombinations(relevant);
}

TEST(ShaderContract, DescriptorsNameEveryCategoryOnceAndGenerateEachNameOnce)
{
  for (const TechniqueDescriptor& descriptor : techniqueRegistry())
  {
    for (const BufferSpec& buffer : descriptor.buffers)
    {
      if (buffer.kind != BufferKind::Categorical)
      {
        EXPECT_TRUE(buffer.categoryIdentifiers.empty()) << descriptor.name << " " << buffer.name;
        continue;
      }
      ASSERT_EQ(buffer.categoryIdentifiers.size(), buffer.categoryLabels.size())
        << descriptor.name << " " << buffer.name << ": one shader identifier per label";
      std::set<std::string> unique;
      for (const std::string& identifier : buffer.categoryIdentifiers)
      {
        EXPECT_TRUE(unique.insert(identifier).second) << descriptor.name << " " << buffer.name << " repeats " << identifier;
        EXPECT_EQ(identifier, upperCase(identifier)) << descriptor.name << " " << buffer.name;
        EXPECT_FALSE(identifier.empty()) << descriptor.name << " " << buffer.name;
      }
    }
    // The preamble defines each name once, category codes at their index and constants at their value.
    const vtkSmartPointer<vtkSLTechniquePass> pass = descriptor.createPass();
    FrameResources frame;
    frame.technique = &descriptor;
    frame.parameters = descriptor.defaultParameters();
    pass->SetFrame(&frame);
    std::map<std::string, std::string> defined;
    for (const auto& [name, value] : PreambleAccess::defines(*pass))
    {
      EXPECT_TRUE(defined.emplace(name, value).second) << descriptor.name << ": the preamble defines " << name << " twice";
    }
    for (const BufferSpec& buffer : descriptor.buffers)
    {
      for (std::size_t code = 0; code < buffer.categoryIdentifiers.size(); ++code)
      {
        EXPECT_EQ(defined[upperCase(buffer.name + "_" + buffer.categoryIdentifiers[code])], std::to_string(code))
          << descriptor.name << " " << buffer.name << " " << buffer.categoryIdentifiers[code];
      }
    }
    for (const ShaderConstant& constant : descriptor.shaderConstants)
    {
      EXPECT_EQ(defined[constant.name], std::to_string(constant.value)) << descriptor.name << " " << constant.name;
    }
  }
}

// One ctest case per technique (ss08's 13 824 variants alone take most of the sweep), so ctest -j spreads them.
class ShaderContractOf : public testing::TestWithParam<std::string>
{
};

TEST_P(ShaderContractOf, EveryVariantOfTheTechniqueShaderKeepsItsDescriptorsContract)
{
  const TechniqueDescriptor& descriptor = findTechnique(GetParam());
  const vtkSmartPointer<vtkSLTechniquePass> pass = descriptor.createPass();
  FrameResources frame;
  frame.technique = &descriptor;
  pass->SetFrame(&frame);
  int programs = 0;
  int failing = 0;
  for (const std::vector<std::string>& combination : shaderRelevantCombinations(descriptor, *pass, frame))
  {
    frame.parameters = descriptor.defaultParameters();
    for (const std::string& assignment : combination)
    {
      frame.parameters.set(assignment);
    }
    for (const std::vector<std::string>& flags : descriptor.shaderFlagSets)
    {
      ShaderDefines defines = PreambleAccess::defines(*pass);
      std::string label = descriptor.name + " " + PreambleAccess::fragmentShaderPath(*pass);
      for (const std::string& assignment : combination)
      {
        label += " " + assignment;
      }
      for (const std::string& flag : flags)
      {
        defines.push_back({ flag, "" });
        label += " #define " + flag;
      }
      const std::string source =
        assembleShader(PreambleAccess::fragmentShaderPath(*pass), defines, PreambleAccess::declarations(*pass));
      const std::vector<std::string> violations = contractViolations(descriptor, defines, source);
      ++programs;
      if (!violations.empty() && ++failing <= 3) // the first few, not hundreds of copies of one mistake
      {
        ADD_FAILURE() << label << ":" << joined(violations);
      }
    }
    // The pass's other shaders (wedges, STSVs), with the same preamble and their own flags.
    for (const PreambleAccess::PassShader& shader : PreambleAccess::passShaders(*pass))
    {
      ShaderDefines defines = PreambleAccess::defines(*pass);
      std::string label = descriptor.name + " " + shader.path;
      for (const std::string& flag : shader.flags)
      {
        defines.push_back({ flag, "" });
        label += " #define " + flag;
      }
      const std::string source = assembleShader(shader.path, defines, PreambleAccess::declarations(*pass));
      const std::vector<std::string> violations = contractViolations(descriptor, defines, source, false);
      ++programs;
      if (!violations.empty() && ++failing <= 3)
      {
        ADD_FAILURE() << label << ":" << joined(violations);
      }
    }
  }
  EXPECT_EQ(failing, 0) << descriptor.name << ": " << failing << " of " << programs << " programs break the contract";
  std::cout << "[ measured ] " << descriptor.name << ": " << programs << " programs checked\n";
}

std::vector<std::string> registeredTechniqueNames()
{
  std::vector<std::string> names;
  for (const TechniqueDescriptor& descriptor : techniqueRegistry())
  {
    names.push_back(descriptor.name);
  }
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, ShaderContractOf, testing::ValuesIn(registeredTechniqueNames()),
  [](const testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  });

// ---------------------------------------------------------------------------------------------------------------
// The records and codes C++ shares with the object-space and structure shaders, each declared once.

// The preamble of dcs's pass for a frame with `samples` light samples, and the pass (it must outlive its frame use).
struct DcsPreamble
{
  TechniqueDescriptor descriptor = findTechnique("dcs");
  FrameResources frame;
  vtkSmartPointer<vtkSLTechniquePass> pass = descriptor.createPass();
  explicit DcsPreamble(int samples)
  {
    frame.technique = &descriptor;
    frame.parameters = descriptor.defaultParameters();
    frame.parameters.set("samples=" + std::to_string(samples));
    pass->SetFrame(&frame);
  }
  ShaderDefines defines() const { return PreambleAccess::defines(*pass); }
  std::map<std::string, std::string> values() const
  {
    const ShaderDefines all = defines();
    return { all.begin(), all.end() };
  }
  std::string assembled(const std::string& path, const std::vector<std::string>& flags = {}) const
  {
    ShaderDefines all = defines();
    for (const std::string& flag : flags)
    {
      all.push_back({ flag, "" });
    }
    return assembleShader(path, all, PreambleAccess::declarations(*pass));
  }
};

// `text` with `line` inserted after the generated preamble (before the shader file's first line).
std::string afterPreamble(const std::string& text, const std::string& line)
{
  const std::size_t at = text.find("// file ");
  EXPECT_NE(at, std::string::npos);
  return text.substr(0, at) + line + "\n" + text.substr(at);
}

TEST(ShaderContract, DcsCounterLayersComeFromTheFramesSampleCount)
{
  for (const int samples : { 16, 64, 256 })
  {
    const DcsCounterLayers layers(samples);
    const std::map<std::string, std::string> defined = DcsPreamble(samples).values();
    EXPECT_EQ(defined.at("DCS_SAMPLE_COUNTER_LAYERS"), std::to_string(samples / 4)) << samples;
    EXPECT_EQ(defined.at("DCS_CHECKSUM_LAYER"), std::to_string(layers.checksum())) << samples;
    EXPECT_EQ(defined.at("DCS_WEIGHTED_CHECKSUM_LAYER"), std::to_string(layers.checksum() + 1)) << samples;
    EXPECT_EQ(defined.at("DCS_COVERING_LAYER"), std::to_string(layers.checksum() + 2)) << samples;
    EXPECT_EQ(defined.at("DCS_COUNTER_LAYERS"), std::to_string(samples / 4 + 3)) << samples;
    EXPECT_EQ(defined.at("DCS_COUNTERS_PER_LAYER"), "4");
    EXPECT_EQ(defined.at("DCS_COUNTER_BITS"), "8");
    EXPECT_EQ(DcsCounterLayers::replicated(kDcsCounterBias), 0x80808080u);
  }
}

TEST(ShaderContract, RecordLayoutsComeFromTheirCppDeclarations)
{
  for (const char* technique : { "dcs", "penumbra-wedge" })
  {
    const TechniqueDescriptor& descriptor = findTechnique(technique);
    std::map<std::string, int> constants;
    for (const ShaderConstant& constant : descriptor.shaderConstants)
    {
      constants[constant.name] = constant.value;
    }
    EXPECT_EQ(constants.at("WEDGE_RECORD_VEC4"), 4) << technique;
    EXPECT_EQ(constants.at("WEDGE_RECORD_OPPOSITE"), 2) << technique;
    EXPECT_EQ(constants.at("STSV_RECORD_VEC4"), 11) << technique;
    EXPECT_EQ(constants.at("STSV_RECORD_TEXTURE_ROW1"), 10) << technique;
  }
}

TEST(ShaderContract, TheObjectSpaceShadersFailWithTheirOldHandCopies)
{
  const DcsPreamble preamble(16);
  const TechniqueDescriptor& descriptor = preamble.descriptor;
  const ShaderDefines defines = preamble.defines();
  const std::string wedges = preamble.assembled("dcs/DcsWedgeUpdate.glsl");
  ASSERT_TRUE(contractViolations(descriptor, defines, wedges, false).empty())
    << joined(contractViolations(descriptor, defines, wedges, false));
  // The counter layers as DcsSampleCounters.glsl defined them.
  const std::vector<std::string> layer = contractViolations(
    descriptor, defines, afterPreamble(wedges, "#define DCS_CHECKSUM_LAYER (lightSampleCount / 4)"), false);
  EXPECT_TRUE(mentions(layer, "#defines DCS_CHECKSUM_LAYER, which the descriptor generates")) << joined(layer);
  // The wedge record read as the shader read it.
  const std::vector<std::string> wedge = contractViolations(descriptor, defines,
    replaced(wedges, "wedgeRecordVec4(wedgeIndex, WEDGE_RECORD_V1)", "wedgeData[4 * wedgeIndex + 1]"), false);
  EXPECT_TRUE(mentions(wedge, "reads a record as wedgeData[4 * wedgeIndex + 1] with the literal 4")) << joined(wedge);
  // The STSV record's stride as StsvSamples.glsl kept it.
  const std::string stsv = preamble.assembled("stsv/StsvSamples.glsl", { "STSV_DCS_COUNTERS" });
  ASSERT_TRUE(contractViolations(descriptor, defines, stsv, false).empty());
  const std::vector<std::string> stride = contractViolations(descriptor, defines,
    replaced(replaced(stsv, "StsvRecord readStsvRecord", "const int STSV_RECORD = 11;\nStsvRecord readStsvRecord"),
      "wedgeData[STSV_RECORD_VEC4 * index + field]", "wedgeData[STSV_RECORD * index + field]"),
    false);
  EXPECT_TRUE(mentions(stride, "declares STSV_RECORD, a copy of the layout of record STSV_RECORD")) << joined(stride);
  // The counter packing written out.
  const std::vector<std::string> packing = contractViolations(descriptor, defines,
    afterPreamble(stsv, "const int DCS_COUNTER_BITS = 8;"), false);
  EXPECT_TRUE(mentions(packing, "declares const DCS_COUNTER_BITS, which the descriptor generates")) << joined(packing);
}

TEST(ShaderContract, TheMicrorectBuildUsesTheClaimCodesOfItsCppTwin)
{
  EXPECT_EQ(MicrorectClaims::kB | MicrorectClaims::kD | MicrorectClaims::kE, 7); // distinct bits
  const TechniqueDescriptor none;
  for (const int pass : { 1, 2 })
  {
    const ShaderDefines defines = microrectBuildDefines(pass);
    const std::map<std::string, std::string> defined(defines.begin(), defines.end());
    EXPECT_EQ(defined.at("CLAIMED_B"), std::to_string(MicrorectClaims::kB));
    EXPECT_EQ(defined.at("CLAIMED_D"), std::to_string(MicrorectClaims::kD));
    EXPECT_EQ(defined.at("CLAIMED_E"), std::to_string(MicrorectClaims::kE));
    const std::string source = assembleShader("microrect/MicrorectBuild.glsl", defines);
    const std::vector<std::string> violations = contractViolations(none, defines, source, false);
    EXPECT_TRUE(violations.empty()) << "pass " << pass << joined(violations);
    // The codes as the shader kept them.
    const std::vector<std::string> copied =
      contractViolations(none, defines, afterPreamble(source, "const uint CLAIMED_B = 1u;"), false);
    EXPECT_TRUE(mentions(copied, "declares const CLAIMED_B, which the descriptor generates")) << joined(copied);
  }
}

} // namespace
} // namespace sl
