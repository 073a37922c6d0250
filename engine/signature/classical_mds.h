// Classical multidimensional scaling (Torgerson 1952; Gower 1966): points in `dims` dimensions
// whose Euclidean distances approximate a given distance matrix, the first step of the paper's
// unsupervised classification (Aristidou et al. 2018, section 6.1: MDS of the signature
// distances, then k-means).
//
//   B = -1/2 J D^(2) J        (D^(2): the squared distances; J = I - 1 1^T / n, double centring)
//   X = V_dims diag(sqrt(max(lambda, 0)))   (the dims largest eigenpairs of B)
//
// For a Euclidean D in at most dims dimensions, X reproduces D exactly (up to a rigid motion).
// Eigenvectors' signs are fixed (the largest-magnitude entry of each is made positive), so the
// result does not depend on the eigensolver's choice of sign. Dense eigensolver (Eigen) below
// 2,000 points, Spectra's Lanczos solver for the top eigenpairs above.
// Thread-safety: a pure function.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"

namespace motif {

struct MdsResult {
  Eigen::MatrixXd coordinates;      // n x dims
  std::vector<double> eigenvalues;  // the dims largest of B, descending (negative ones kept)
};

// InvalidArgument: a matrix that is not square and symmetric with a zero diagonal, non-finite or
// negative entries, dims = 0 or dims >= n (with n >= 2; one point gives the origin).
Result<MdsResult> ClassicalMds(const Eigen::MatrixXd& distances, uint32_t dims);

}  // namespace motif
