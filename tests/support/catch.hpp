//! \file catch.hpp
//! \brief One include for Catch2 v3 or v2 (Debian bookworm ships 2.13), so tests build with either.
//! The version is the one CMake found (BLASTSIM_CATCH2_V3), not whatever headers the compiler sees first.
#pragma once
#if defined(BLASTSIM_CATCH2_V3)
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_floating_point.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>
namespace Catch {
//! v2's substring matcher under its v2 name.
inline Matchers::StringContainsMatcher Contains(const std::string& s) { return Matchers::ContainsSubstring(s); }
}  // namespace Catch
#else
#include <catch2/catch.hpp>
#endif
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
