//! \file checkpoint_fwd.hpp
//! \brief Declarations of the checkpoint writer and reader (checkpoint.hpp) for the headers whose classes write
//! and read their own records.
#pragma once

namespace blastsim {
class CheckpointWriter;
class CheckpointReader;
}  // namespace blastsim
