// The `--set key=value` knob registry: one table that knows every key, its value type and range,
// and which layer owns it. Each layer describes its own keys (scene::knobSpecs(),
// render::rendererKnobSpecs(), ...) without knowing the others; the CLI registers the union and
// checks every assignment before any work starts, so a misspelt key or an out-of-range value is
// exit 2 naming the key (and listing the known ones) instead of a silently ignored setting.
#pragma once

#include <array>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace fgb {

enum class KnobType {
  Integer,  // decimal integer in [min, max]
  Number,   // finite decimal number in [min, max] (an end is open when minExclusive/maxExclusive)
  Flag,     // 0|1|true|false|on|off
  Word,     // one of `words`
  Vec3,     // three finite numbers "x,y,z"
  Text,     // any non-empty text (checked by its owner when used, e.g. a pass name)
  // One of `words` (built-in names), or the path of a user's FILE.json, which its owner reads and
  // checks when used (render.path: a render path file).
  WordOrFile,
};

// What a knob does to a sweep's reference image (docs/sweep.md, "The reference"). Every knob has
// one; KnobRegistry::add refuses a spec without it, so a new knob cannot be added unclassified.
enum class ReferenceRole {
  Unset,
  // Trades accuracy for speed (sampling, light caps, cluster slices, LOD error): the reference sets
  // it to `exact`, the value at which the approximation is exact (or converged).
  Approximation,
  // Part of the intended image (bloom, exposure, tone mapping, debug views): copied from the
  // configuration. A look knob that a sweep varies is judged against the scene's own value of it,
  // and the error column then reads "change from the scene's look".
  Look,
  // What is rendered (scene, camera, geometry, lights): copied from the configuration; each value of
  // a varied content knob gets a reference of its own.
  Content,
  // Changes the cost and at most the path's bias, not what is approximated (render path, depth
  // prepass, backing, occlusion, debug timing): pinned to `exact` (empty: dropped, the scene's
  // own), so configurations that differ only in these share one reference.
  CostOnly,
};

struct KnobSpec {
  std::string key;
  KnobType type = KnobType::Number;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minExclusive = false;
  bool maxExclusive = false;
  // Word: the allowed values. Integer/Number: words accepted besides numbers (e.g. "inf", "auto").
  std::vector<std::string> words;
  std::string owner;  // "scene" | "renderer" | ...: the layer that applies it
  std::string help;   // one short phrase
  ReferenceRole role = ReferenceRole::Unset;
  std::string exact;  // Approximation: the reference's value; CostOnly: the pinned value ("" = dropped)
};

// A knob's value once checked and converted, by the one parser of its type (parseKnobValue):
// Integer and Number as a double (or, for one of their `words`, that word), Flag as a bool, Word,
// Text and WordOrFile as the text, Vec3 as three doubles. Layers take values in this form, so a
// value is parsed (and checked) once, not kept as text and parsed again where it is used.
using KnobVec3 = std::array<double, 3>;
using KnobValue = std::variant<double, bool, std::string, KnobVec3>;

// `text` checked against `spec` and converted; InputError "--set key=text: expected ..." (one line)
// when it is of the wrong type or out of range.
KnobValue parseKnobValue(const KnobSpec& spec, std::string_view text);
// The same without throwing: nullopt where parseKnobValue throws.
std::optional<KnobValue> tryParseKnobValue(const KnobSpec& spec, std::string_view text);

// `spec` with its reference role (and the reference's value for Approximation / CostOnly knobs).
KnobSpec withRole(KnobSpec spec, ReferenceRole role, std::string exact = {});

// "approximation", "look", "content", "cost-only" (sweep.json, docs).
const char* referenceRoleName(ReferenceRole role);

class KnobRegistry {
 public:
  // Adds a layer's keys; a key registered twice, one without a reference role, or an Approximation
  // knob without its exact value is a programming error (std::logic_error).
  void add(const std::vector<KnobSpec>& specs);

  [[nodiscard]] const KnobSpec* find(std::string_view key) const;
  [[nodiscard]] const std::vector<KnobSpec>& specs() const { return specs_; }

  // Throws fgb::InputError "--set key=value: ..." (one line) for an unknown key, naming the known
  // ones, and for a value of the wrong type or out of range, saying what was expected.
  void check(const std::string& key, const std::string& value) const;
  void checkAll(const std::map<std::string, std::string>& knobs) const;
  // check(), returning the converted value (parseKnobValue).
  [[nodiscard]] KnobValue parse(const std::string& key, const std::string& value) const;

  // "a, b, c": every key, sorted.
  [[nodiscard]] std::string knownKeys() const;

 private:
  std::vector<KnobSpec> specs_;
};

// What a spec accepts, in words: "an integer in [1, 4]", "0|1", "a number > 0 or inf", ...
std::string describeExpected(const KnobSpec& spec);

// True when `value` is acceptable for `spec` (type and range): tryParseKnobValue has a value.
bool knobValueValid(const KnobSpec& spec, std::string_view value);

// Splits "key=value" assignments (InputError "--set X: expected key=value" when one has no '=' or
// no key). A later assignment of the same key wins.
std::map<std::string, std::string> splitKnobAssignments(const std::vector<std::string>& assignments);

}  // namespace fgb
