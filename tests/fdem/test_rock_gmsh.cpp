//! \file test_rock_gmsh.cpp
//! \brief FDEM validation on Gmsh meshes: F2 (Lame cylinder), F6 (Brazilian disc), F8 (uniaxial compression).
