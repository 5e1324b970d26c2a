// The keys of a unit SPEC ("NAME:key=value,..."): the reader every unit's build uses, how a build
// writes a key's resolved value back, and the keys every unit shares (formats, skip, merge buffer,
// tables).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fixed/fixed_point.h"
#include "units/key_table.h"
#include "units/unit.h"

namespace glint {

// Reads the keys of one spec, each once; a key the unit does not have is an error.
class KeyReader {
 public:
  // `known`: every key the unit takes (common keys included).
  KeyReader(const UnitSpec& spec, const std::vector<UnitKey>& known);

  // A declared key (key_table.h): its value, checked against the declaration, or its default.
  // Keys are read only through their declarations, so that no build states a default or a range
  // of its own.
  QFormat read(const FormatKey& k) const;
  int read(const IntKey& k) const;
  bool read(const FlagKey& k) const;
  std::string read(const ChoiceKey& k) const;
  std::optional<double> read(const RealKey& k) const;  // nullopt: absent or "none"

  // The key's text as given (nullptr: absent).
  const std::string* find(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& why) const;

 private:
  QFormat format(const std::string& key, QFormat def) const;
  // An integer in lo..hi; allow_auto: "auto" gives def.
  int integer(const std::string& key, int def, int lo, int hi, bool allow_auto) const;
  // A finite real number x with lo <= x < hi; nullopt when the key is absent.
  std::optional<double> real(const std::string& key, double lo, double hi) const;
  bool flag(const std::string& key, bool def) const;
  std::string choice(const std::string& key, const std::string& def,
                     const std::vector<std::string>& allowed) const;

  const UnitSpec& spec_;
};

// How a refusal names the keys whose values cause it, as KeyReader::fail does for one key: "key
// 'out' = 'uq1.40'", or for a width derived from several, "keys 'in' = 'uq1.50', 'out' =
// 'uq1.30'". The datapaths refuse with the values they were built from, not the spec's text, so a
// key left at "auto" is stated with what it resolved to: "'guard' = 'auto' (4)".
struct KeyValue {
  std::string key, value;
};
std::string key_values(const std::vector<KeyValue>& kv);
std::string auto_value(bool given, long long resolved);

// A key's resolved value into a built unit's config (its description, and through make_unit_set
// its canonical spec), under the key's declared name. A choice the canonical form leaves out at its
// default, and a real key at "none", are not written.
void put_key(nlohmann::json& config, const FormatKey& k, const QFormat& value);
void put_key(nlohmann::json& config, const IntKey& k, int value);
void put_key(nlohmann::json& config, const FlagKey& k, bool value);
void put_key(nlohmann::json& config, const ChoiceKey& k, std::string_view value);
void put_key(nlohmann::json& config, const RealKey& k, std::optional<double> value);

// The keys every unit has (CommonKeyTable), listed first by `glint units`.
std::vector<UnitKey> common_keys();

// Their values for one spec.
struct CommonKeys {
  QFormat in = CommonKeyTable::in.def;
  QFormat out = CommonKeyTable::out.def;
  bool skip = CommonKeyTable::skip.def;
  int buffer = CommonKeyTable::buffer.def;  // merge-buffer entries; kAutoInt: latency + 3
  // tables=ram: per-slot tables (thresholds, every per-material table) as registers with a write
  // port, loaded when the materials load; rom (default): case ROMs of the scene's materials.
  bool tables_ram = CommonKeyTable::tables.def == "ram";
};
CommonKeys read_common_keys(const KeyReader& keys);

inline const char* on_off(bool b) {
  return b ? "on" : "off";
}

}  // namespace glint
