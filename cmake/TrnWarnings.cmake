# Warnings and floating-point rules applied to every trnkit target.
add_library(trn_options INTERFACE)
target_compile_options(trn_options INTERFACE
  -Wall -Wextra -Wpedantic -Wno-unused-parameter
  # Scoring positions must round each product and sum on its own on every backend (scoring.hpp).
  -ffp-contract=off)
