#include "engine/signature/classical_mds.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>
#include <Eigen/Eigenvalues>

namespace motif {
namespace {

constexpr Eigen::Index kDenseLimit = 2000;

}  // namespace

Result<MdsResult> ClassicalMds(const Eigen::MatrixXd& distances, uint32_t dims) {
  const Eigen::Index n = distances.rows();
  if (distances.cols() != n || n == 0) {
    return Status::InvalidArgument("MDS: the distance matrix must be square and not empty");
  }
  if (dims == 0 || (n >= 2 && dims >= n)) {
    return Status::InvalidArgument("MDS: " + std::to_string(dims) + " dimensions for " +
                                   std::to_string(n) + " points (1 to n - 1)");
  }
  for (Eigen::Index row = 0; row < n; ++row) {
    if (distances(row, row) != 0) return Status::InvalidArgument("MDS: a non-zero diagonal");
    for (Eigen::Index col = 0; col < n; ++col) {
      const double value = distances(row, col);
      if (!std::isfinite(value) || value < 0 || value != distances(col, row)) {
        return Status::InvalidArgument("MDS: entry (" + std::to_string(row) + ", " +
                                       std::to_string(col) +
                                       ") is negative, not finite or not symmetric");
      }
    }
  }
  MdsResult result;
  if (n == 1) {
    result.coordinates = Eigen::MatrixXd::Zero(1, dims);
    result.eigenvalues.assign(dims, 0.0);
    return result;
  }
  // B = -1/2 J D2 J: subtract row and column means, add the grand mean.
  Eigen::MatrixXd b = distances.array().square().matrix();
  const Eigen::VectorXd row_means = b.rowwise().mean();
  const double grand_mean = row_means.mean();
  b.colwise() -= row_means;
  b.rowwise() -= row_means.transpose();
  b.array() += grand_mean;
  b *= -0.5;
  b = 0.5 * (b + b.transpose()).eval();  // exactly symmetric

  Eigen::VectorXd values(dims);
  Eigen::MatrixXd vectors(n, dims);
  if (n <= kDenseLimit) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(b);
    if (solver.info() != Eigen::Success) return Status::InvalidArgument("MDS: eigensolver failed");
    // Ascending: the largest are last.
    for (uint32_t dim = 0; dim < dims; ++dim) {
      values(dim) = solver.eigenvalues()(n - 1 - dim);
      vectors.col(dim) = solver.eigenvectors().col(n - 1 - dim);
    }
  } else {
    Spectra::DenseSymMatProd<double> op(b);
    const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * dims + 1, 20));
    Spectra::SymEigsSolver<Spectra::DenseSymMatProd<double>> solver(op, dims, ncv);
    solver.init();
    solver.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10);
    if (solver.info() != Spectra::CompInfo::Successful) {
      return Status::InvalidArgument("MDS: the Lanczos eigensolver did not converge");
    }
    values = solver.eigenvalues();
    vectors = solver.eigenvectors();
  }
  result.coordinates.resize(n, dims);
  for (uint32_t dim = 0; dim < dims; ++dim) {
    Eigen::Index largest = 0;
    vectors.col(dim).cwiseAbs().maxCoeff(&largest);
    const double sign = vectors(largest, dim) < 0 ? -1.0 : 1.0;
    result.coordinates.col(dim) = sign * std::sqrt(std::max(values(dim), 0.0)) * vectors.col(dim);
    result.eigenvalues.push_back(values(dim));
  }
  return result;
}

}  // namespace motif
