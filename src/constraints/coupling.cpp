// §3.11 general coupling: Σ c_k q_k − c_0 = 0 over two or three joint coordinates;
// CouplingConstraint is CouplerConstraint itself (coupler.cpp) under its own family
// name, so that diagnostics say "COUPLING". Nothing else to define here: the file
// keeps the one-family-per-file layout of src/constraints.
#include "constraints/couplers.hpp"
