// SPDX-License-Identifier: MIT
// The OpenCL C++ bindings as the backend uses them: OpenCL 1.2 (what every current driver and POCL offer),
// errors as exceptions. Included by the backend's sources only.
#pragma once
#define CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#include <CL/opencl.hpp>
#pragma GCC diagnostic pop
