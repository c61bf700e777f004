//! \file bad.cpp
//! \brief A fixture of scripts/check-idiom.py: one violation of each rule (tests/scripts/test_check_idiom.sh); never compiled.
#include <thrust/sort.h>
namespace x {
struct Leaky {           // a kernel functor in a .cpp, with raw pointers
  double* out;
  const int *a, *b;
  double Rec::*field;    // pointer to member: fine
  BLAST_HD void operator()(index_t k) const { out[k] = a[k]; }
};
void f() {
  DeviceVector<int> keys;                  // a loose array
  DeviceVector<double>& ref = g();         // a reference: fine
  thrust::sort(thrust::device, keys.begin(), keys.end());
  for_each_index("x", 3, [=] BLAST_HD(index_t k) { });
  // thrust::in_a_comment and "thrust::in_a_string" are fine
}
}
