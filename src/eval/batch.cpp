#include "eval/evaluate.h"
#include "eval/parallel.h"

namespace glint {

void Evaluator::add_batch(const VectorRow* rows, std::size_t count, BatchResults& out,
                          int threads) {
  out.rows = count;
  out.reference.resize(count);
  out.raw.resize(units_.size() * count);
  out.skipped.resize(units_.size() * count);
  // The reference is shared by every lane: computed once per row, in halves when there are threads.
  std::vector<RowReference> refs(count);
  std::vector<std::size_t> slot(count);
  const std::size_t chunk = 4096;
  parallel_for((count + chunk - 1) / chunk, threads, [&](std::size_t c) {
    const std::size_t end = std::min(count, (c + 1) * chunk);
    for (std::size_t i = c * chunk; i < end; ++i) {
      slot[i] = slots_.slot(rows[i]);
      refs[i] = make_reference(slots_, slot[i], rows[i].t, display_bits_);
      out.reference[i] = refs[i].value;
    }
  });
  parallel_for(units_.size(), threads, [&](std::size_t u) {
    const SpecularUnit& unit = *units_[u];
    const QFormat in = unit.in_format();
    std::int64_t* raw = out.raw.data() + u * count;
    std::uint8_t* skipped = out.skipped.data() + u * count;
    for (std::size_t i = 0; i < count; ++i) {
      const std::int64_t t_raw = quantize_input(rows[i].t, in);
      const bool sk = unit.skip(slot[i], t_raw);
      raw[i] = sk ? 0 : unit.eval(slot[i], t_raw);
      skipped[i] = sk;
      lanes_[u].add(slot[i], refs[i], t_raw, sk, raw[i]);
    }
  });
}

}  // namespace glint
