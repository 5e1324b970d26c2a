/* Reference vectors for glint's Tesla SFU model (src/units/sfu/tesla_sfu.h), from envytools'
   bit-exact model of the hardware (nvhw/sfu.c, nvhw/sfu_tab.c, nvhw/fp.c at commit f102b823).
   Not built by glint: tests/units/data/README.md says how to run it. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "nvhw/fp.h"
#include "nvhw/sfu.h"

static uint32_t bits(float f) {
  uint32_t u;
  memcpy(&u, &f, 4);
  return u;
}
static uint64_t lcg = 0x2545F4914F6CDD1DULL;
static uint32_t rnd(void) {
  lcg = lcg * 6364136223846793005ULL + 1442695040888963407ULL;
  return (uint32_t)(lcg >> 33);
}

int main(void) {
  /* lg2: every one of the 64 segments of every binade below 1 a uq1.15 t reaches (from 2^-15),
     at the segment's ends and at a random offset, and of [1, 2) (where the result keeps the most
     fraction bits: it pins every table entry) at 38 random offsets; then the special inputs. */
  for (int e = 127 - 15; e <= 127; ++e)
    for (uint32_t seg = 0; seg < 64; ++seg) {
      uint32_t offs[40] = {0, 0x1ffff};
      for (int k = 2; k < 40; ++k) offs[k] = rnd() & 0x1ffff;
      for (int k = 0; k < (e == 127 ? 40 : 3); ++k) {
        uint32_t x = (uint32_t)e << 23 | seg << 17 | offs[k];
        printf("lg2 %08x %08x\n", x, sfu_lg2(x));
      }
    }
  uint32_t lg2_special[] = {0x00000000, 0x80000000, 0x3f800000, 0x7f800000, 0xff800000,
                            0x7fc00000, 0xbf800000, 0x00000001, 0x007fffff, 0x40000000};
  for (unsigned i = 0; i < sizeof lg2_special / 4; ++i)
    printf("lg2 %08x %08x\n", lg2_special[i], sfu_lg2(lg2_special[i]));
  /* pre.ex2 then ex2: x = i + f for integer parts -24..0 and f at every segment's last code and a
     random offset, and specials. The column is pre's output, then ex2's. */
  for (int ip = -24; ip <= 0; ++ip)
    for (uint32_t seg = 0; seg < 64; ++seg) {
      uint32_t offs[2] = {0x1ffff, rnd() & 0x1ffff};
      for (int k = 0; k < 2; ++k) {
        double f = (double)(seg << 17 | offs[k]) / (double)(1u << 23);
        uint32_t x = bits((float)(ip + f));
        uint32_t p = sfu_pre(x, SFU_PRE_EX2);
        printf("ex2 %08x %08x %08x\n", x, p, sfu_ex2(p));
      }
    }
  uint32_t ex2_special[] = {0x00000000, 0x80000000, 0x7f800000, 0xff800000, 0x7fc00000,
                            0x43000000, 0xc3000000, 0x42fe0000, 0xc2fc0000, 0x00000001,
                            0x80000001, 0x33800000, 0xb3800000};
  for (unsigned i = 0; i < sizeof ex2_special / 4; ++i) {
    uint32_t p = sfu_pre(ex2_special[i], SFU_PRE_EX2);
    printf("ex2 %08x %08x %08x\n", ex2_special[i], p, sfu_ex2(p));
  }
  /* The highlight as a shader computes it: lg2 t, fmul (round to nearest, flush to zero) by n,
     pre.ex2, ex2; t every 256th code of uq1.15 plus the codes next to 0 and 1, n a spread of
     uq14.4 values. Columns: t, n, lg2, product, pre, ex2. */
  const double ns[] = {0.0625, 0.5, 1, 2, 5, 10, 20, 50, 128, 1000, 4096, 16383.9375};
  for (unsigned j = 0; j < sizeof ns / sizeof ns[0]; ++j)
    for (int c = 0; c <= 32768; ++c) {
      if (c % 256 != 0 && c > 2 && c < 32766) continue;
      uint32_t t = bits((float)(c / 32768.0)), n = bits((float)ns[j]);
      uint32_t l = sfu_lg2(t), m = fp32_mul(l, n, FP_RN | FP_FTZ);
      uint32_t p = sfu_pre(m, SFU_PRE_EX2);
      printf("pow %08x %08x %08x %08x %08x %08x\n", t, n, l, m, p, sfu_ex2(p));
    }
  return 0;
}
