// The quadratic-interpolation tables of NVIDIA's Tesla-class special-function unit for ex2 and lg2,
// 64 segments each: {A, B, C} with the value A + B r + C r^2 on the segment (r: 17 bits, the
// segment's offset; tesla_sfu.cpp). Data, not code: the bit-exact contents reverse-engineered and
// checked against G80-GT200 hardware by the envytools project, file nvhw/sfu_tab.c at commit
// f102b823 (https://github.com/envytools/envytools), published under the MIT licence:
//
//   Copyright (C) 2015 Marcelina Kościelnicka <mwk@0x04.net>. All Rights Reserved.
//   Permission is hereby granted, free of charge, to any person obtaining a copy of this software
//   and associated documentation files (the "Software"), to deal in the Software without
//   restriction, including without limitation the rights to use, copy, modify, merge, publish,
//   distribute, sublicense, and/or sell copies of the Software, and to permit persons to whom the
//   Software is furnished to do so, subject to the following conditions: The above copyright
//   notice and this permission notice (including the next paragraph) shall be included in all
//   copies or substantial portions of the Software. THE SOFTWARE IS PROVIDED "AS IS", WITHOUT
//   WARRANTY OF ANY KIND, EXPRESS OR IMPLIED.
//
// Coefficient widths as Oberman & Siu describe the design ("A high-performance area-efficient
// multifunction interpolator", ARITH-17, 2005): A 26 bits, B 16, C 10 (signed for lg2).
#include "units/sfu/tesla_sfu.h"

namespace glint::tesla_sfu {

// 2^x / 2, ln 2 * 2^x / 2, (ln 2)^2 * 2^x scaled: the segments of x in [0, 1).
const Table kEx2Table = {{
    {0x2000000, 0x58b9, 494}, {0x2059347, 0x59b0, 501}, {0x20b361b, 0x5aaa, 506},
    {0x210e8a2, 0x5ba7, 511}, {0x216ab0f, 0x5ca6, 518}, {0x21c7d86, 0x5da9, 521},
    {0x2226039, 0x5eae, 527}, {0x2285356, 0x5fb6, 532}, {0x22e5709, 0x60c0, 541},
    {0x2346b7e, 0x61ce, 546}, {0x23a90e5, 0x62df, 551}, {0x240c772, 0x63f2, 559},
    {0x2470f4e, 0x6509, 564}, {0x24d68ad, 0x6623, 568}, {0x253d3c0, 0x673f, 577},
    {0x25a50b6, 0x685f, 583}, {0x260dfc2, 0x6982, 589}, {0x2678117, 0x6aa8, 596},
    {0x26e34e6, 0x6bd2, 600}, {0x274fb67, 0x6cfe, 609}, {0x27bd4c9, 0x6e2e, 615},
    {0x282c145, 0x6f61, 622}, {0x289c10b, 0x7098, 627}, {0x290d456, 0x71d2, 633},
    {0x297fb5a, 0x730f, 641}, {0x29f364e, 0x7450, 647}, {0x2a6856a, 0x7594, 655},
    {0x2ade8e7, 0x76dc, 661}, {0x2b560fb, 0x7827, 670}, {0x2bcede2, 0x7976, 677},
    {0x2c48fd7, 0x7ac8, 686}, {0x2cc4710, 0x7c1f, 691}, {0x2d413cc, 0x7d79, 699},
    {0x2dbf648, 0x7ed7, 705}, {0x2e3eebe, 0x8038, 715}, {0x2ebfd6a, 0x819e, 721},
    {0x2f4228e, 0x8307, 730}, {0x2fc5e67, 0x8474, 739}, {0x304b134, 0x85e5, 748},
    {0x30d1b33, 0x875b, 753}, {0x3159ca8, 0x88d4, 763}, {0x31e35d3, 0x8a51, 773},
    {0x326e6f7, 0x8bd3, 779}, {0x32fb054, 0x8d59, 787}, {0x3389230, 0x8ee3, 796},
    {0x3418ccf, 0x9071, 806}, {0x34aa076, 0x9204, 813}, {0x353cd6a, 0x939b, 822},
    {0x35d13f4, 0x9536, 833}, {0x3667457, 0x96d6, 842}, {0x36feede, 0x987b, 849},
    {0x37983d3, 0x9a24, 858}, {0x383337d, 0x9bd1, 870}, {0x38cfe27, 0x9d84, 877},
    {0x396e41c, 0x9f3b, 887}, {0x3a0e5aa, 0xa0f7, 896}, {0x3ab031d, 0xa2b7, 909},
    {0x3b53cc1, 0xa47d, 917}, {0x3bf92e7, 0xa648, 925}, {0x3ca05dd, 0xa817, 938},
    {0x3d495f5, 0xa9ec, 946}, {0x3df437f, 0xabc5, 959}, {0x3ea0ecc, 0xada4, 969},
    {0x3f4f831, 0xaf88, 980},
}};

// log2 m, log2(e) / m / 2, -log2(e) / m^2 scaled: the segments of m in [1, 2).
const Table kLg2Table = {{
    {0x4, 0xb8a8, -727},       {0x16e797, 0xb5d1, -705},  {0x2d75ad, 0xb310, -685},
    {0x43ace7, 0xb064, -665},  {0x598fe2, 0xadcc, -646},  {0x6f210f, 0xab47, -627},
    {0x8462c9, 0xa8d5, -610},  {0x995750, 0xa674, -592},  {0xae00d8, 0xa424, -576},
    {0xc26162, 0xa1e4, -559},  {0xd67af5, 0x9fb4, -544},  {0xea4f76, 0x9d93, -530},
    {0xfde0b9, 0x9b81, -518},  {0x111307c, 0x997c, -504}, {0x124407c, 0x9784, -491},
    {0x1371251, 0x9599, -479}, {0x149a786, 0x93ba, -466}, {0x15c01a8, 0x91e7, -455},
    {0x16e2222, 0x9020, -445}, {0x1800a59, 0x8e63, -433}, {0x191bbac, 0x8cb2, -425},
    {0x1a33760, 0x8b0a, -414}, {0x1b47ebe, 0x896c, -404}, {0x1c592fb, 0x87d8, -396},
    {0x1d6753f, 0x864c, -385}, {0x1e726aa, 0x84ca, -377}, {0x1f7a857, 0x8350, -368},
    {0x207fb52, 0x81df, -361}, {0x218209f, 0x8076, -354}, {0x2281942, 0x7f14, -346},
    {0x237e627, 0x7dba, -339}, {0x247883b, 0x7c67, -331}, {0x257006a, 0x7b1c, -326},
    {0x2664f8d, 0x79d7, -319}, {0x2757682, 0x7898, -311}, {0x2847614, 0x7761, -307},
    {0x2934f0d, 0x762f, -300}, {0x2a20233, 0x7503, -293}, {0x2b0904a, 0x73de, -289},
    {0x2befa00, 0x72be, -283}, {0x2cd4011, 0x71a3, -276}, {0x2db632e, 0x708e, -271},
    {0x2e963fd, 0x6f7e, -266}, {0x2f7431d, 0x6e74, -262}, {0x305013a, 0x6d6e, -257},
    {0x3129eee, 0x6c6d, -253}, {0x3201cc6, 0x6b71, -249}, {0x32d7b5d, 0x6a79, -244},
    {0x33abb41, 0x6985, -238}, {0x347dd00, 0x6896, -234}, {0x354e121, 0x67ac, -232},
    {0x361c823, 0x66c5, -227}, {0x36e9293, 0x65e2, -223}, {0x37b40e4, 0x6503, -219},
    {0x387d398, 0x6428, -216}, {0x3944b1e, 0x6350, -211}, {0x3a0a7ec, 0x627d, -209},
    {0x3acea7a, 0x61ac, -204}, {0x3b91337, 0x60df, -201}, {0x3c52285, 0x6016, -199},
    {0x3d118da, 0x5f4f, -195}, {0x3dcf690, 0x5e8c, -192}, {0x3e8bc12, 0x5dcc, -189},
    {0x3f469c1, 0x5d0f, -186},
}};

}  // namespace glint::tesla_sfu
