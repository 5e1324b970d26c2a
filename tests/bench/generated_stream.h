// The speed programs' generated stream: t uniform over [t_min, 1] from a 64-bit LCG (Knuth's MMIX
// multiplier and increment) with one fixed seed, row k from the state after k + 1 steps. sim_speed,
// sweep_speed, eval_speed and the Verilator driver (verilator_speed.cpp, built outside CMake: this
// header needs nothing but <cstdint>) all draw their rows from here, so glint and Verilator are
// timed on the same requests (verilator_speed.sh checks that both skip the same ones).
#pragma once

#include <cstdint>

namespace glint::bench {

constexpr std::uint64_t kStreamSeed = 0x243F6A8885A308D3ULL;
constexpr std::uint64_t kLcgMul = 6364136223846793005ULL, kLcgAdd = 1442695040888963407ULL;

constexpr std::uint64_t lcg_step(std::uint64_t state) {
  return state * kLcgMul + kLcgAdd;
}

// The row's t from the generator's state: its top 53 bits spread over [t_min, 1).
inline double stream_t(std::uint64_t state, double t_min) {
  return t_min + static_cast<double>(state >> 11) * 0x1.0p-53 * (1.0 - t_min);
}

}  // namespace glint::bench
