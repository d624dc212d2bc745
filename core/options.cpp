#include "core/options.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace tray {
namespace {

const char* typeWord(OptionType type) {
  switch (type) {
    case OptionType::kInt:
      return "an integer";
    case OptionType::kFloat:
      return "a number";
    case OptionType::kBool:
      return "true or false";
    case OptionType::kString:
      return "text";
  }
  return "a value";
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// A range bound as the user typed it: integers without a decimal point.
std::string formatBound(double v, OptionType type) {
  if (type == OptionType::kInt) return std::to_string(int64_t(v));
  return formatOptionValue(OptionValue(float(v)));
}

[[noreturn]] void reject(const OptionSpec& s, const std::string& text, const std::string& why) {
  throw Error("--" + s.name + " " + text + ": expected " + why);
}

OptionSpec make(std::string name, OptionType type, OptionValue def, std::string help) {
  OptionSpec s;
  s.name = std::move(name);
  s.type = type;
  s.defaultValue = std::move(def);
  s.help = std::move(help);
  return s;
}

}  // namespace

std::string rangeText(const OptionSpec& s) {
  const bool lo = std::isfinite(s.min), hi = std::isfinite(s.max);
  if (lo && hi) return formatBound(s.min, s.type) + ".." + formatBound(s.max, s.type);
  const std::string what = s.type == OptionType::kInt ? "an integer " : "a finite value ";
  if (lo) return what + ">= " + formatBound(s.min, s.type);
  if (hi) return what + "<= " + formatBound(s.max, s.type);
  return "";
}

OptionSpec intOption(std::string name, int64_t defaultValue, int64_t min, int64_t max,
                     std::string help) {
  OptionSpec s = make(std::move(name), OptionType::kInt, defaultValue, std::move(help));
  // INT64_MAX: no upper bound (a seed), which a double could not state exactly anyway.
  s.min = double(min);
  s.max = max == std::numeric_limits<int64_t>::max() ? s.max : double(max);
  return s;
}

OptionSpec floatOption(std::string name, float defaultValue, float min, float max,
                       std::string help) {
  OptionSpec s = make(std::move(name), OptionType::kFloat, defaultValue, std::move(help));
  s.min = min, s.max = max;
  return s;
}

OptionSpec flagOption(std::string name, std::string help) {
  return make(std::move(name), OptionType::kBool, false, std::move(help));
}

OptionSpec choiceOption(std::string name, std::string defaultValue,
                        std::vector<std::string> choices, std::string help) {
  OptionSpec s =
      make(std::move(name), OptionType::kString, std::move(defaultValue), std::move(help));
  s.choices = std::move(choices);
  return s;
}

OptionSpec diagnostic(OptionSpec spec) {
  spec.affectsPixels = false;
  return spec;
}

std::string formatOptionValue(const OptionValue& value) {
  switch (OptionType(value.index())) {
    case OptionType::kInt:
      return std::to_string(std::get<int64_t>(value));
    case OptionType::kFloat: {
      // The shortest text that reads back as the same float: 0.03, not 0.0299999993.
      const float v = std::get<float>(value);
      char text[32];
      for (int digits = 6; digits <= 9; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, double(v));
        if (std::strtof(text, nullptr) == v) break;
      }
      return text;
    }
    case OptionType::kBool:
      return std::get<bool>(value) ? "true" : "false";
    case OptionType::kString:
      return std::get<std::string>(value);
  }
  return "";
}

OptionValue parseOptionValue(const OptionSpec& spec, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  switch (spec.type) {
    case OptionType::kInt: {
      errno = 0;
      const long long v = std::strtoll(begin, &end, 10);
      if (text.empty() || *end || errno) reject(spec, text, typeWord(spec.type));
      return int64_t(v);
    }
    case OptionType::kFloat: {
      // strtof, not strtod: a decimal rounds to float once, as the renderer's literals do.
      const float v = std::strtof(begin, &end);
      if (text.empty() || *end) reject(spec, text, typeWord(spec.type));
      return v;
    }
    case OptionType::kBool:
      if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
      if (text == "false" || text == "0" || text == "off" || text == "no") return false;
      reject(spec, text, typeWord(spec.type));
    case OptionType::kString:
      return text;
  }
  return text;
}

void validateOptionValue(const OptionSpec& s, const OptionValue& value) {
  const std::string text = formatOptionValue(value);
  const auto type = OptionType(value.index());
  const bool numberForFloat = s.type == OptionType::kFloat && type == OptionType::kInt;
  if (type != s.type && !numberForFloat) reject(s, text, typeWord(s.type));
  if (s.type == OptionType::kInt || s.type == OptionType::kFloat) {
    const double v = type == OptionType::kInt ? double(std::get<int64_t>(value))
                                               : double(std::get<float>(value));
    if (!std::isfinite(v) || v < s.min || v > s.max)
      reject(s, text, rangeText(s).empty() ? "a finite number" : rangeText(s));
  }
  if (s.type == OptionType::kString && !s.choices.empty()) {
    for (const auto& c : s.choices)
      if (c == text) return;
    reject(s, text, "one of " + joined(s.choices));
  }
}

std::string describeOption(const OptionSpec& s) {
  std::string d = s.help + " (default " + formatOptionValue(s.defaultValue);
  if (s.type == OptionType::kBool) d = s.help + " (default off";
  const std::string range = rangeText(s);
  if (!range.empty()) d += "; " + range;
  if (!s.choices.empty()) d += "; " + joined(s.choices);
  return d + ")";
}

void OptionValues::declare(const std::vector<OptionSpec>& specs) {
  for (const OptionSpec& s : specs)
    if (!find(s.name)) declared_.push_back(s);
}

const OptionSpec* OptionValues::find(const std::string& name) const {
  for (const OptionSpec& s : declared_)
    if (s.name == name) return &s;
  return nullptr;
}

OptionValue OptionValues::value(const std::string& name) const {
  const auto given = given_.find(name);
  const OptionSpec* spec = find(name);
  if (given == given_.end()) {
    if (!spec) throw Error("unknown option --" + name, Error::Kind::kRender);
    return spec->defaultValue;
  }
  // A float option set from an integer (settings.set("aa-threshold", 1)) reads as a float.
  if (spec && spec->type == OptionType::kFloat && given->second.index() == size_t(OptionType::kInt))
    return float(std::get<int64_t>(given->second));
  return given->second;
}

namespace {

template <class T>
T typed(const OptionValue& v, const std::string& name, OptionType type) {
  if (const T* p = std::get_if<T>(&v)) return *p;
  throw Error("--" + name + " " + formatOptionValue(v) + ": expected " + typeWord(type));
}

}  // namespace

int64_t OptionValues::getInt64(const std::string& name) const {
  return typed<int64_t>(value(name), name, OptionType::kInt);
}

int OptionValues::getInt(const std::string& name) const {
  return int(getInt64(name));
}

float OptionValues::getFloat(const std::string& name) const {
  const OptionValue v = value(name);
  if (const int64_t* i = std::get_if<int64_t>(&v)) return float(*i);
  return typed<float>(v, name, OptionType::kFloat);
}

bool OptionValues::getBool(const std::string& name) const {
  return typed<bool>(value(name), name, OptionType::kBool);
}

std::string OptionValues::getString(const std::string& name) const {
  return typed<std::string>(value(name), name, OptionType::kString);
}

void OptionValues::validate() const {
  for (const auto& [name, v] : given_)
    if (const OptionSpec* spec = find(name)) validateOptionValue(*spec, v);
}

}  // namespace tray
