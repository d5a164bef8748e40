// Identity of the example target (included from scratch_target.v).
`define SCRATCH_VENDOR 16'h1234
`define SCRATCH_DEVICE 16'h5C7A
`define SCRATCH_CLASS  24'h058000
