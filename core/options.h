#pragma once
// Options declared once (docs/options-design.md): each option is one OptionSpec beside the code
// that reads it. The command line, validation, the farm job signature and the EXR metadata are all
// generated from these specs, so adding an option touches no other file. No CLI11 here: the
// command-line layer (cli/option_cli.h) turns specs into CLI11 options.
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace tray {

enum class OptionType { kInt, kFloat, kBool, kString };

/// A typed value; the alternative's index is the OptionType.
using OptionValue = std::variant<int64_t, float, bool, std::string>;

/// One option: its command-line spelling, type, default, valid values and help.
struct OptionSpec {
  std::string name;  ///< the CLI spelling without dashes: "aa-threshold" (--aa-threshold)
  OptionType type = OptionType::kString;
  OptionValue defaultValue;
  std::string help;
  double min = -std::numeric_limits<double>::infinity();  ///< kInt, kFloat: inclusive range
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices;  ///< kString: the accepted values (empty: any text)
  /// Whether the value can change the pixels: such options go into the farm job signature and
  /// the EXR metadata; the others (diagnostics) do not.
  bool affectsPixels = true;
};

/// An integer option in [min, max].
OptionSpec intOption(std::string name, int64_t defaultValue, int64_t min, int64_t max,
                     std::string help);
/// A float option in [min, max]; an infinite bound still excludes NaN and infinities.
OptionSpec floatOption(std::string name, float defaultValue, float min, float max,
                       std::string help);
/// A flag (default false).
OptionSpec flagOption(std::string name, std::string help);
/// One of `choices` (empty: any text).
OptionSpec choiceOption(std::string name, std::string defaultValue,
                        std::vector<std::string> choices, std::string help);
/// The same spec marked as not changing the pixels (kept out of the job signature).
OptionSpec diagnostic(OptionSpec spec);

/// The value as text: integers in decimal, floats in the fewest digits (6 to 9) that read back
/// as the same float, flags as true/false.
std::string formatOptionValue(const OptionValue& value);
/// Parses command-line text as the spec's type; throws tray::Error naming the option.
OptionValue parseOptionValue(const OptionSpec& spec, const std::string& text);
/// Throws tray::Error "--name value: expected ..." unless `value` is valid for `spec` (type,
/// range, choices). An int given for a float option is accepted.
void validateOptionValue(const OptionSpec& spec, const OptionValue& value);
/// The spec's range as text: "0..12", "an integer >= 0", or "" for none (and for non-numbers).
std::string rangeText(const OptionSpec& spec);
/// The help text with the default and the valid values: "... (default 4; 0..12)".
std::string describeOption(const OptionSpec& spec);

/// Named option values over a set of declared specs. A name reads as the value set for it,
/// else its declared default; reading a name neither declared nor set throws tray::Error.
class OptionValues {
 public:
  /// Adds specs; a name declared already keeps its first declaration (the outer integrator's).
  void declare(const std::vector<OptionSpec>& specs);
  const std::vector<OptionSpec>& declared() const { return declared_; }
  /// The declared spec of `name`, or null.
  const OptionSpec* find(const std::string& name) const;

  /// Sets a value (validated by validate(), not here, so that an option may be set before the
  /// integrator that declares it is known).
  template <class T>
  void set(const std::string& name, const T& value) {
    if constexpr (std::is_same_v<T, bool>)
      setValue(name, OptionValue(value));
    else if constexpr (std::is_integral_v<T>)
      setValue(name, OptionValue(int64_t(value)));
    else if constexpr (std::is_floating_point_v<T>)
      setValue(name, OptionValue(float(value)));
    else
      setValue(name, OptionValue(std::string(value)));
  }
  void setValue(const std::string& name, OptionValue value) { given_[name] = std::move(value); }
  bool isSet(const std::string& name) const { return given_.count(name) != 0; }
  /// The values set explicitly (command line or code), by name.
  const std::map<std::string, OptionValue>& given() const { return given_; }

  /// The value of `name`: set or default. Throws tray::Error for an unknown name.
  OptionValue value(const std::string& name) const;
  int getInt(const std::string& name) const;
  int64_t getInt64(const std::string& name) const;
  float getFloat(const std::string& name) const;
  bool getBool(const std::string& name) const;
  std::string getString(const std::string& name) const;

  /// Checks every value set for a declared name against its spec (throws tray::Error).
  void validate() const;

 private:
  std::vector<OptionSpec> declared_;
  std::map<std::string, OptionValue> given_;
};

}  // namespace tray
