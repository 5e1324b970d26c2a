// A unit's keys, each declared once (src/units/<unit>/keys.h, and CommonKeyTable in keys.h): name,
// what it takes, default and meaning. From the declaration come the config's default (a Config
// member is initialized from its key's `def`), the check of a given value (KeyReader::read), the
// line `glint units` prints, the canonical spec (which keys it names, in which order, and which it
// leaves out at their default) and the keys reference (src/units/keys.md).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "fixed/fixed_point.h"
#include "units/common.h"

namespace glint {

// A key as the catalogue lists it: `glint units` prints key, default and meaning; `values` (what
// the key takes) is for the keys reference.
struct UnitKey {
  std::string key;
  std::string meaning;
  std::string default_value;
  std::string values = {};
};

// The default of an integer key the build resolves ("auto": from other keys or the scene).
inline constexpr int kAutoInt = -1;

// A fixed-point format, uqI.F or sqI.F.
struct FormatKey {
  std::string_view name;
  QFormat def;
  std::string_view doc;
};

// An integer in lo..hi; takes_auto: "auto" is also taken (def kAutoInt: resolved by the build).
struct IntKey {
  std::string_view name;
  int def;
  int lo, hi;
  std::string_view doc;
  bool takes_auto = false;
};

// on|off (also 1|0, true|false, yes|no).
struct FlagKey {
  std::string_view name;
  bool def;
  std::string_view doc;
};

// One of a fixed list of words. in_canonical_at_default false: a spec at the default leaves the key
// out of its canonical form, so that specs and goldens written before the key existed keep their
// bytes.
struct ChoiceKey {
  template <std::size_t N>
  constexpr ChoiceKey(std::string_view name_, std::string_view def_,
                      const std::string_view (&allowed_)[N], std::string_view doc_,
                      bool in_canonical_at_default_ = true)
      : name(name_),
        def(def_),
        allowed(allowed_),
        count(N),
        doc(doc_),
        in_canonical_at_default(in_canonical_at_default_) {}

  std::vector<std::string> choices() const { return {allowed, allowed + count}; }

  std::string_view name;
  std::string_view def;
  const std::string_view* allowed;
  std::size_t count;
  std::string_view doc;
  bool in_canonical_at_default;
};

// A real number x with lo <= x < hi, or "none" (the default: the key is left out of the canonical
// spec).
struct RealKey {
  std::string_view name;
  double lo, hi;
  std::string_view doc;
};

// The catalogue's line of each kind of key.
UnitKey key_entry(const FormatKey& k);
UnitKey key_entry(const IntKey& k);
UnitKey key_entry(const FlagKey& k);
UnitKey key_entry(const ChoiceKey& k);
UnitKey key_entry(const RealKey& k);

// A unit's keys in catalogue order (the order `glint units` lists and canonical specs write).
template <class... Key>
std::vector<UnitKey> key_list(const Key&... keys) {
  return {key_entry(keys)...};
}

// The keys every unit has, listed first by `glint units`.
struct CommonKeyTable {
  static constexpr FormatKey in{"in", kDefaultIn,
                                "input format of t (clamped to [0, 1], rounded to nearest)"};
  static constexpr FormatKey out{"out", kDefaultOut, "output format of the highlight"};
  static constexpr FlagKey skip{
      "skip", true,
      "tau comparator on|off: skips t where the unit's own output is <= eps_K/c_y, never above "
      "Källberg's tau (eq.5, §3)"};
  static constexpr IntKey buffer{
      "buffer",
      kAutoInt,
      1,
      1 << 16,
      "merge-buffer entries (timing; auto: latency + 3, full throughput)",
      true};
  static constexpr std::string_view kTables[] = {"rom", "ram"};
  static constexpr ChoiceKey tables{
      "tables", "rom", kTables,
      "per-slot tables (tau thresholds, per-material tables) as rom: case ROMs of the scene's "
      "materials, or ram: registers with a write port (glint rtl: cfg_*), loaded at run time",
      false};
};

}  // namespace glint
