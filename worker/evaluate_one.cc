#include "worker/evaluate_one.h"

#include <fstream>
#include <iterator>
#include <sstream>

#include "animat/v1/isolation.pb.h"
#include "common/evaluation/model_config.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "worker/evaluation_pool.h"

namespace animat {
namespace {

// The request, checked as a Welcome and a Work from the master would be.
Status ReadRequest(const std::string& path, v1::IsolatedEvaluation* request,
                   ModelConfig* config) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in || !request->ParseFromString(bytes.str())) {
    return Status::InvalidArgument(path +
                                   ": not an animat.v1.IsolatedEvaluation");
  }
  if (request->build_id() != protocol::BuildId()) {
    return Status::InvalidArgument(
        path + ": made by build \"" + request->build_id() + "\", this is \"" +
        protocol::BuildId() + "\" (results could differ in the last bits)");
  }
  Status status = ConfigFromProto(request->config(), config);
  if (!status.ok()) return status.WithPrefix(path + ": the configuration");
  if (protocol::ConfigHash(request->config()) != request->config_hash()) {
    return Status::InvalidArgument(path + ": the configuration's hash differs");
  }
  if (request->item().individual() > protocol::kMaxIndividual) {
    return Status::InvalidArgument(path + ": individual out of range");
  }
  return Status::Ok();
}

}  // namespace

int EvaluateOne(const std::string& request_path, const std::string& result_path,
                const LogSink& log) {
  v1::IsolatedEvaluation request;
  ModelConfig config;
  Status status = ReadRequest(request_path, &request, &config);
  if (!status.ok()) {
    log(status.message());
    return kCannotEvaluateOne;
  }
  const v1::WorkResult result = EvaluateItem(request.item(), config);
  std::ofstream out(result_path, std::ios::binary | std::ios::trunc);
  if (!out || !result.SerializeToOstream(&out) || !out.flush()) {
    log(result_path + ": cannot write the result");
    return kCannotEvaluateOne;
  }
  return kEvaluatedOne;
}

}  // namespace animat
