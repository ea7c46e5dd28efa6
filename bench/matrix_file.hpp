#pragma once
// A sparse matrix written for NumPy (bench/*_vs_scipy.py read it): the full symmetric matrix
// in compressed columns, int64 n, int64 nnz, int64 outer[n + 1], int32 inner[nnz],
// float64 values[nnz] (little-endian, what numpy.fromfile reads).
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "dampbound/physics/stiffness.hpp"

namespace dampbound::bench {

inline void write_matrix(const SparseMatrix& A, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const long long n = A.rows(), nnz = A.nonZeros();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(&nnz), sizeof nnz);
  for (long long k = 0; k <= n; ++k) {
    const long long o = A.outerIndexPtr()[k];
    out.write(reinterpret_cast<const char*>(&o), sizeof o);
  }
  out.write(reinterpret_cast<const char*>(A.innerIndexPtr()), static_cast<std::streamsize>(nnz * 4));
  out.write(reinterpret_cast<const char*>(A.valuePtr()), static_cast<std::streamsize>(nnz * 8));
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(2);
  }
}

}  // namespace dampbound::bench
