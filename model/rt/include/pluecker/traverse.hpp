// SPDX-License-Identifier: MIT
// The whole BVH traversal, one header for code that uses much of it:
//   traversal.hpp       box test and child order, counters, Tracer, make_tracer
//   accel.hpp           Accel, the memory layout the traversal reads
//   box_kernels.hpp     the float box tests inline, one box and node pairs
//   policies.hpp        the box tests as traversal policies
//   traverse_loops.hpp  the traversal loops, traverse()
//   batched.hpp         the batched, resumable traversal (hardware in the loop)
#pragma once

#include "pluecker/accel.hpp"
#include "pluecker/batched.hpp"
#include "pluecker/box_kernels.hpp"
#include "pluecker/policies.hpp"
#include "pluecker/traversal.hpp"
#include "pluecker/traverse_loops.hpp"
