//! \file catch_main.cpp
//! \brief Catch2 v2 main (v3 provides Catch2::Catch2WithMain instead).
#define CATCH_CONFIG_MAIN
#include "catch.hpp"
