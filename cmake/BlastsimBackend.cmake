# Selects the kernel backend. CPU: g++ with Thrust's OpenMP device system (Debian's libthrust-dev, or the
# CUDA toolkit's CCCL when Debian's is absent). CUDA: nvcc compiles every kernel source (LANGUAGE CUDA).
include_guard(GLOBAL)

if(BLASTSIM_ENABLE_CUDA)
  if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
    set(CMAKE_CUDA_ARCHITECTURES 90)  # Hopper (H100); override with -DCMAKE_CUDA_ARCHITECTURES=...
  endif()
  enable_language(CUDA)
  set(CMAKE_CUDA_STANDARD 17)
  set(CMAKE_CUDA_STANDARD_REQUIRED ON)
  find_package(CUDAToolkit REQUIRED)
  set(BLASTSIM_BACKEND "cuda")
else()
  find_package(OpenMP REQUIRED COMPONENTS CXX)
  find_path(BLASTSIM_THRUST_INCLUDE_DIR thrust/version.h
            PATHS /usr/include /usr/local/cuda/include/cccl /usr/local/cuda/include
            DOC "Directory holding thrust/ (Debian libthrust-dev or the CUDA toolkit's CCCL)")
  if(NOT BLASTSIM_THRUST_INCLUDE_DIR)
    message(FATAL_ERROR "Thrust not found: install Debian's libthrust-dev (apt-get install libthrust-dev) "
                        "or set BLASTSIM_THRUST_INCLUDE_DIR")
  endif()
  set(BLASTSIM_BACKEND "cpu-openmp")
endif()
message(STATUS "blastsim backend: ${BLASTSIM_BACKEND}")

# Marks kernel sources as CUDA in a CUDA build (MFEM/AMReX style: sources stay .cpp).
function(blastsim_kernel_sources)
  if(BLASTSIM_ENABLE_CUDA)
    set_source_files_properties(${ARGN} PROPERTIES LANGUAGE CUDA)
  endif()
endfunction()

# Links VTK to a library that writes ParaView files (BLASTSIM_HAVE_VTK in its sources) when the build has it.
function(blastsim_use_vtk target)
  if(BLASTSIM_VTK_ACTIVE)
    target_link_libraries(${target} PRIVATE ${VTK_LIBRARIES})
    target_compile_definitions(${target} PRIVATE BLASTSIM_HAVE_VTK=1)
  endif()
endfunction()

# Common warning set for project targets, and the sanitizers' instrumentation when BLASTSIM_SANITIZE is set.
function(blastsim_warnings target)
  target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic>)
  if(BLASTSIM_SANITIZE)
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-fsanitize=${BLASTSIM_SANITIZE} -fno-omit-frame-pointer>)
  endif()
endfunction()

# blastsim_add_library(<name> EXPORT <export name> SOURCES <files...> [KERNEL_SOURCES <files...>]):
# a static library blastsim_<name> with alias blastsim::<export name>, public headers in include/, linked
# to blastsim::core, installed and exported. KERNEL_SOURCES are compiled by nvcc in a CUDA build.
function(blastsim_add_library name)
  cmake_parse_arguments(L "" "EXPORT" "SOURCES;KERNEL_SOURCES" ${ARGN})
  blastsim_kernel_sources(${L_KERNEL_SOURCES})
  set(target blastsim_${name})
  add_library(${target} STATIC ${L_SOURCES} ${L_KERNEL_SOURCES})
  add_library(blastsim::${L_EXPORT} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${L_EXPORT} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC blastsim::core)
  blastsim_warnings(${target})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(TARGETS ${target} EXPORT blastsimTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()
