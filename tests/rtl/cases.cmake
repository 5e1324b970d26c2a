# The co-simulation cases of ctest label `rtl`: NAME|SPEC|glint rtl input options. Every unit at
# its default and at least two other specs; the testbench runs every input code of every slot and,
# with --vectors, the trace's rows, under the sink pattern of --sink-ready. The `.ram` cases write
# every per-slot table as registers with a write port (tables=ram), which the testbench loads
# before the stream; multi-material inputs, so that the group addressing of the RAMs is exercised.
set(GLINT_RTL_CASES
  "lut.default|lut|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "lut.bits4|lut:bits=4,table_frac=20|--vectors traces/multi_light.vec --sink-ready 0.3 --seed 5"
  "lut.narrow_skip_off|lut:bits=9,in=uq1.7,out=uq1.10,skip=off|--vectors traces/eight_lights.vec --sink-ready 0.8"
  "hast.default|hast|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "hast.d3_materials|hast:d=3|--vectors traces/blinn_colored.vec"
  "hast.auto_d|hast:d=auto,match=minimax|--vectors traces/multi_light.vec --sink-ready 0.5"
  "hast.d1_narrow|hast:d=1,in=uq1.9,out=uq1.8,guard=0|--vectors traces/gaussian.vec --sink-ready 0.4"
  "horner.default|horner|--vectors traces/phong_basic.vec --sink-ready 0.7"
  "horner.full_ls|horner:degree=2,domain=full,method=ls|--vectors traces/blinn_colored.vec"
  "horner.wide|horner:degree=10,guard=12|--vectors traces/phong_basic.vec --sink-ready 0.5"
  "horner.deg6_lights|horner:degree=6,guard=8|--vectors traces/eight_lights.vec --sink-ready 0.9 --seed 3"
  "pow.default|pow|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "pow.small_tables|pow:log_bits=6,exp_bits=4,in=uq1.16,out=uq1.10|--vectors traces/multi_light.vec --sink-ready 0.5"
  "pow.n_wide|pow:n=uq14.6,y_frac=16,log_frac=20|--vectors traces/contract_cases.vec --sink-ready 0.9 --seed 11"
  "schlick.default|schlick|--vectors traces/phong_basic.vec --sink-ready 0.7"
  "schlick.iterative|schlick:divider=iterative,n=uq10.2|--vectors traces/gaussian.vec"
  "schlick.minimax_narrow|schlick:match=minimax,in=uq1.12,out=uq1.10|--vectors traces/hard_cases.vec --sink-ready 0.4"
  "lut.ram|lut:tables=ram|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "lut.ram_bits4|lut:tables=ram,bits=4,table_frac=20,in=uq1.12|--vectors traces/multi_light.vec --sink-ready 0.5"
  "hast.ram|hast:tables=ram|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "hast.ram_auto_d|hast:tables=ram,d=auto,match=minimax,in=uq1.12|--vectors traces/blinn_colored.vec --sink-ready 0.5"
  "horner.ram|horner:tables=ram|--vectors traces/phong_basic.vec --sink-ready 0.7"
  "horner.ram_full|horner:tables=ram,degree=3,domain=full,in=uq1.12|--vectors traces/multi_light.vec --sink-ready 0.5"
  "pow.ram|pow:tables=ram|--vectors traces/phong_basic.vec --sink-ready 0.6"
  "pow.ram_small_tables|pow:tables=ram,log_bits=6,exp_bits=4,in=uq1.12,out=uq1.10|--vectors traces/blinn_colored.vec --sink-ready 0.5"
  "schlick.ram|schlick:tables=ram|--vectors traces/phong_basic.vec --sink-ready 0.7"
  "schlick.ram_iterative|schlick:tables=ram,divider=iterative,in=uq1.12|--vectors traces/multi_light.vec"
)
