#include "engine/words/take_classification.h"

#include <algorithm>
#include <map>
#include <set>

#include "engine/evaluation/adjusted_rand_index.h"
#include "engine/signature/k_means.h"

namespace motif {

Result<TakeClassification> ClassifyTakes(Eigen::MatrixXd distances,
                                         const std::vector<std::string>& labels,
                                         const ClassifyOptions& options) {
  const size_t n = labels.size();
  if (distances.rows() != static_cast<Eigen::Index>(n) || distances.cols() != distances.rows()) {
    return Status::InvalidArgument("classify: a distance matrix of another size than the takes");
  }
  if (n < 2) return Status::InvalidArgument("classify: at least 2 takes are needed");
  if (options.knn == 0) return Status::InvalidOption("knn", "must be at least 1");
  if (options.top == 0) return Status::InvalidOption("top", "must be at least 1");
  if (options.dims == 0) return Status::InvalidOption("dims", "must be at least 1");
  TakeClassification result;
  result.distances = std::move(distances);
  std::set<std::string> names;
  for (const std::string& label : labels) {
    if (!label.empty()) names.insert(label);
  }
  result.label_names.assign(names.begin(), names.end());
  for (const std::string& label : labels) {
    if (label.empty()) {
      result.labels.push_back(kUnlabelled);
    } else {
      result.labels.push_back(static_cast<uint32_t>(
          std::lower_bound(result.label_names.begin(), result.label_names.end(), label) -
          result.label_names.begin()));
    }
  }

  // Unsupervised: MDS, then k-means.
  const uint32_t dims = std::min<uint32_t>(options.dims, static_cast<uint32_t>(n - 1));
  MOTIF_ASSIGN_OR_RETURN(result.mds, ClassicalMds(result.distances, dims));
  uint32_t groups = options.groups;
  if (groups == 0)
    groups = result.label_names.empty() ? 8 : static_cast<uint32_t>(result.label_names.size());
  groups = std::min<uint32_t>(groups, static_cast<uint32_t>(n));
  const RowMatrixXf points = result.mds.coordinates.cast<float>();
  KMeansOptions kmeans;
  kmeans.seed = options.seed;
  kmeans.threads = options.threads;
  // Fewer distinct points than groups (identical takes): fewer groups.
  for (kmeans.k = groups; kmeans.k >= 1; --kmeans.k) {
    Result<KMeansResult> clustered = RunKMeans(points, kmeans);
    if (clustered.ok()) {
      result.groups = std::move(clustered->assignments);
      result.group_count = kmeans.k;
      break;
    }
    if (kmeans.k == 1) return clustered.status();
  }
  std::vector<uint32_t> truth;
  std::vector<uint32_t> found;
  for (size_t take = 0; take < n; ++take) {
    if (result.labels[take] == kUnlabelled) continue;
    truth.push_back(result.labels[take]);
    found.push_back(result.groups[take]);
  }
  if (!truth.empty()) {
    result.adjusted_rand_index = AdjustedRandIndex(truth, found);
    std::map<uint32_t, std::map<uint32_t, uint64_t>> counts;
    for (size_t idx = 0; idx < truth.size(); ++idx) ++counts[found[idx]][truth[idx]];
    uint64_t majority = 0;
    for (const auto& [group, by_label] : counts) {
      uint64_t most = 0;
      for (const auto& [label, count] : by_label) most = std::max(most, count);
      majority += most;
    }
    result.purity = static_cast<double>(majority) / static_cast<double>(truth.size());
  }

  // Supervised.
  result.knn = LeaveOneOutKnn(result.distances, result.labels,
                              static_cast<uint32_t>(result.label_names.size()), options.knn);
  result.top = options.top;
  result.precision_at_top = PrecisionAtK(result.distances, result.labels, options.top);
  for (uint32_t take = 0; take < n; ++take) {
    result.nearest.push_back(NearestItems(result.distances, result.labels, take, options.top,
                                          /*labelled_only=*/false));
  }
  return result;
}

nlohmann::json ClassificationJson(const TakeClassification& result, const std::string& archive) {
  nlohmann::json json;
  json["version"] = 1;
  json["archive"] = archive;
  json["distance"] = result.distance;
  json["labels"] = result.label_names;
  json["groups"] = result.group_count;
  json["mds_eigenvalues"] = result.mds.eigenvalues;
  const bool labelled = !result.label_names.empty();
  if (labelled) {
    json["unsupervised"] = {{"adjusted_rand_index", result.adjusted_rand_index},
                            {"purity", result.purity}};
    nlohmann::json confusion = nlohmann::json::array();
    for (const auto& row : result.knn.confusion) confusion.push_back(row);
    json["supervised"] = {{"k", result.knn.k},
                          {"labelled", result.knn.labelled},
                          {"correct", result.knn.correct},
                          {"accuracy", result.knn.accuracy},
                          {"confusion", confusion}};
    json["retrieval"] = {{"top", result.top}, {"precision", result.precision_at_top}};
  }
  json["seconds_distances"] = result.seconds_distances;
  nlohmann::json takes = nlohmann::json::array();
  for (size_t take = 0; take < result.names.size(); ++take) {
    nlohmann::json entry;
    entry["clip"] = result.names[take];
    entry["label"] = result.labels[take] == kUnlabelled
                         ? nlohmann::json(nullptr)
                         : nlohmann::json(result.label_names[result.labels[take]]);
    entry["group"] = result.groups[take];
    std::vector<double> coordinates(static_cast<size_t>(result.mds.coordinates.cols()));
    for (Eigen::Index dim = 0; dim < result.mds.coordinates.cols(); ++dim) {
      coordinates[static_cast<size_t>(dim)] =
          result.mds.coordinates(static_cast<Eigen::Index>(take), dim);
    }
    entry["mds"] = coordinates;
    if (labelled) {
      entry["predicted"] = result.knn.predicted[take] == kUnlabelled
                               ? nlohmann::json(nullptr)
                               : nlohmann::json(result.label_names[result.knn.predicted[take]]);
    }
    nlohmann::json nearest = nlohmann::json::array();
    for (uint32_t other : result.nearest[take]) {
      nearest.push_back({{"clip", result.names[other]},
                         {"distance", result.distances(static_cast<Eigen::Index>(take), other)}});
    }
    entry["nearest"] = nearest;
    takes.push_back(entry);
  }
  json["takes"] = takes;
  return json;
}

}  // namespace motif
