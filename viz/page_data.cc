#include "viz/page_data.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

// Written by hand rather than by protobuf's JSON printer, by measurement
// (docs/formats.md, "Replay page"): a ReplayPage message printed by
// MessageToJsonString gave the same frames and size (-0.2%) but took 6.1
// to 6.2 times the instructions (callgrind; 61 M → 374 M for the sample
// genome's page, 301 M → 1864 M for a trace of every step), nearly all in
// its double printing (snprintf with 15 digits, then strtod to check). It
// also prints non-finite values as strings, 64-bit integers as strings and
// leaves out empty fields, which the page would have to undo.
namespace animat::viz {
namespace {

using google::protobuf::RepeatedField;

// With 4 decimals, trailing zeros dropped; null when not finite.
void AppendRounded(double value, std::string* out) {
  if (!std::isfinite(value)) {
    out->append("null");
    return;
  }
  char text[400];  // The longest double in fixed notation has 309 digits.
  const std::to_chars_result end = std::to_chars(
      text, text + sizeof(text), value, std::chars_format::fixed, 4);
  std::string_view digits(text, end.ptr - text);
  while (digits.back() == '0') digits.remove_suffix(1);
  if (digits.back() == '.') digits.remove_suffix(1);
  if (digits == "-0") digits = "0";
  out->append(digits);
}

// The shortest text that reads back to the same double.
void AppendExact(double value, std::string* out) {
  if (!std::isfinite(value)) {
    out->append("null");
    return;
  }
  char text[64];
  const std::to_chars_result end =
      std::to_chars(text, text + sizeof(text), value);
  out->append(text, end.ptr);
}

void AppendString(std::string_view value, std::string* out) {
  out->push_back('"');
  for (const char c : value) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out->push_back('\\');
      out->push_back(c);
    } else if (u < 0x20 || c == '<' || c == '>' || c == '&') {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\u%04x", u);
      out->append(escape);
    } else {
      out->push_back(c);
    }
  }
  out->push_back('"');
}

void AppendArray(const RepeatedField<double>& values, std::string* out) {
  out->push_back('[');
  for (int i = 0; i < values.size(); ++i) {
    if (i > 0) out->push_back(',');
    AppendRounded(values[i], out);
  }
  out->push_back(']');
}

std::string Where(const char* array, int index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

const char* PhaseName(v1::MotionFrame::Phase phase) {
  return phase == v1::MotionFrame::EQUILIBRATION ? "equilibration" : "motion";
}

std::string StatusName(const v1::EvaluationResult& result) {
  std::string name = v1::EvaluationResult::Status_Name(result.status());
  std::transform(name.begin(), name.end(), name.begin(), [](char c) {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  });
  return name;
}

Status CheckSnapshot(int k, const v1::DevelopmentSnapshot& snapshot,
                     const v1::DevelopmentSnapshot* previous) {
  const int cells = snapshot.x_size();
  if (snapshot.y_size() != cells || snapshot.radius_size() != cells) {
    return Status::InvalidArgument(
        Where("development", k) + ": x, y and radius have " +
        std::to_string(cells) + ", " + std::to_string(snapshot.y_size()) +
        " and " + std::to_string(snapshot.radius_size()) + " values");
  }
  if (previous != nullptr && snapshot.step() <= previous->step()) {
    return Status::InvalidArgument(
        Where("development", k) + ": step " + std::to_string(snapshot.step()) +
        " does not follow step " + std::to_string(previous->step()));
  }
  return Status::Ok();
}

Status CheckFrame(int k, const v1::MotionFrame& frame,
                  const v1::MotionFrame* previous, int body_nodes) {
  const std::string where = Where("frames", k);
  if (frame.phase() != v1::MotionFrame::EQUILIBRATION &&
      frame.phase() != v1::MotionFrame::MOTION) {
    return Status::InvalidArgument(where + ": phase is unspecified");
  }
  const int nodes = frame.x_size();
  if (frame.y_size() != nodes) {
    return Status::InvalidArgument(where + ": x and y have " +
                                   std::to_string(nodes) + " and " +
                                   std::to_string(frame.y_size()) + " values");
  }
  for (const int size : {frame.expand_size(), frame.contract_size()}) {
    if (size != 0 && size != nodes) {
      return Status::InvalidArgument(
          where + ": expand and contract need one value per node (" +
          std::to_string(nodes) + ") or none, got " + std::to_string(size));
    }
  }
  if (body_nodes > 0 && nodes != body_nodes) {
    return Status::InvalidArgument(where + ": " + std::to_string(nodes) +
                                   " nodes, the body has " +
                                   std::to_string(body_nodes));
  }
  if (previous == nullptr) return Status::Ok();
  if (frame.phase() < previous->phase() ||
      (frame.phase() == previous->phase() &&
       frame.step() <= previous->step())) {
    return Status::InvalidArgument(where + ": " + PhaseName(frame.phase()) +
                                   " step " + std::to_string(frame.step()) +
                                   " does not follow " +
                                   PhaseName(previous->phase()) + " step " +
                                   std::to_string(previous->step()));
  }
  return Status::Ok();
}

// Appends "name":[a0,b0,a1,b1,...], checking every index.
template <typename Edges>
Status AppendEdges(const char* name, const Edges& edges, int nodes,
                   std::string* out) {
  AppendString(name, out);
  out->append(":[");
  for (int k = 0; k < edges.size(); ++k) {
    const auto& edge = edges[k];
    if (edge.a() >= static_cast<uint32_t>(nodes) ||
        edge.b() >= static_cast<uint32_t>(nodes)) {
      return Status::InvalidArgument(std::string("body.") + Where(name, k) +
                                     ": nodes " + std::to_string(edge.a()) +
                                     " and " + std::to_string(edge.b()) +
                                     ", the body has " + std::to_string(nodes));
    }
    if (k > 0) out->push_back(',');
    out->append(std::to_string(edge.a()) + "," + std::to_string(edge.b()));
  }
  out->append("]");
  return Status::Ok();
}

// The steps of each phase: the configuration's, else the last traced.
void AppendLengths(const v1::Trace& trace, std::string* out) {
  int development = 0, equilibration = 0, motion = 0;
  if (trace.development_size() > 0) {
    development = trace.development(trace.development_size() - 1).step() + 1;
  }
  for (const v1::MotionFrame& frame : trace.frames()) {
    int& last = frame.phase() == v1::MotionFrame::EQUILIBRATION ? equilibration
                                                                : motion;
    last = std::max(last, frame.step());
  }
  const v1::Config& config = trace.config();
  if (config.development().has_steps()) {
    development = config.development().steps();
  }
  if (config.evaluation().has_equilibration_steps()) {
    equilibration = config.evaluation().equilibration_steps();
  }
  if (config.evaluation().has_motion_steps()) {
    motion = config.evaluation().motion_steps();
  }
  out->append("\"lengths\":{\"development\":" + std::to_string(development) +
              ",\"equilibration\":" + std::to_string(equilibration) +
              ",\"motion\":" + std::to_string(motion) + "}");
}

// Model time per equilibration and motion step: the configuration's
// physics.dt, else its default (docs/model.md §7.8).
void AppendDt(const v1::Trace& trace, std::string* out) {
  const v1::PhysicsConfig& physics = trace.config().physics();
  out->append("\"dt\":");
  AppendExact(physics.has_dt() ? physics.dt() : 0.05, out);
}

// "result":{...}; max_overlap (model v3) is exact, or null when absent.
Status AppendResult(const v1::EvaluationResult& result, std::string* out) {
  if (result.has_max_overlap()) {
    const double overlap = result.max_overlap();
    if (!std::isfinite(overlap)) {
      return Status::InvalidArgument("result.max_overlap is not finite");
    }
    if (overlap < 0 || overlap > 1) {
      std::string value;
      AppendExact(overlap, &value);
      return Status::InvalidArgument("result.max_overlap is " + value +
                                     ", not in [0, 1]");
    }
  }
  out->append("\"result\":{\"status\":");
  AppendString(StatusName(result), out);
  out->append(",\"reason\":");
  AppendString(result.reason(), out);
  out->append(",\"fitness\":");
  if (result.has_fitness()) {
    AppendExact(result.fitness(), out);
  } else {
    out->append("null");
  }
  out->append(",\"cells\":" + std::to_string(result.cells()) + ",\"steps\":" +
              std::to_string(result.steps()) + ",\"max_overlap\":");
  if (result.has_max_overlap()) {
    AppendExact(result.max_overlap(), out);
  } else {
    out->append("null");
  }
  out->push_back('}');
  return Status::Ok();
}

// "radii":[r0,r1,...], exact: each body node's radius, 1 where absent
// (body.proto's default).
Status AppendRadii(const v1::Body& body, std::string* out) {
  out->append("\"radii\":[");
  for (int i = 0; i < body.nodes_size(); ++i) {
    const v1::Node& node = body.nodes(i);
    const double radius = node.has_radius() ? node.radius() : 1.0;
    if (!(std::isfinite(radius) && radius > 0)) {
      return Status::InvalidArgument("body." + Where("nodes", i) +
                                     ".radius must be finite and > 0");
    }
    if (i > 0) out->push_back(',');
    AppendExact(radius, out);
  }
  out->push_back(']');
  return Status::Ok();
}

// With guidance (docs/model.md §10.2): "guidance":{"trial":k,
// "decay_length":l,"sources":[x0,y0,x1,y1,...]}, exact values.
Status AppendGuidance(const v1::GuidanceTrace& g, std::string* out) {
  const int sources = g.source_x_size();
  if (g.source_y_size() != sources || sources == 0) {
    return Status::InvalidArgument("guidance: source_x and source_y have " +
                                   std::to_string(sources) + " and " +
                                   std::to_string(g.source_y_size()) +
                                   " values (one per trial, at least one)");
  }
  if (g.trial() < 0 || g.trial() >= sources) {
    return Status::InvalidArgument("guidance: trial " +
                                   std::to_string(g.trial()) + " of " +
                                   std::to_string(sources) + " sources");
  }
  if (!(std::isfinite(g.decay_length()) && g.decay_length() > 0)) {
    return Status::InvalidArgument(
        "guidance: decay_length must be finite and > 0");
  }
  out->append(",\"guidance\":{\"trial\":" + std::to_string(g.trial()) +
              ",\"decay_length\":");
  AppendExact(g.decay_length(), out);
  out->append(",\"sources\":[");
  for (int k = 0; k < sources; ++k) {
    if (!std::isfinite(g.source_x(k)) || !std::isfinite(g.source_y(k))) {
      return Status::InvalidArgument("guidance: " + Where("sources", k) +
                                     " is not finite");
    }
    if (k > 0) out->push_back(',');
    AppendExact(g.source_x(k), out);
    out->push_back(',');
    AppendExact(g.source_y(k), out);
  }
  out->append("]}");
  return Status::Ok();
}

}  // namespace

Result<std::string> PageDataJson(const v1::Trace& trace,
                                 const PageOptions& options) {
  if (trace.development_size() == 0 && trace.frames_size() == 0) {
    std::string message =
        "the trace has nothing to show (status " + StatusName(trace.result());
    if (!trace.result().reason().empty()) {
      message += ": " + trace.result().reason();
    }
    return Status::InvalidArgument(message + ")");
  }
  if (!(options.neutral_rate >= 0) || !std::isfinite(options.neutral_rate)) {
    return Status::InvalidArgument("the neutral rate must be finite and >= 0");
  }
  const int body_nodes = trace.body().nodes_size();

  std::string out = "{\"format\":1,\"title\":";
  AppendString(options.title, &out);
  out.append(",");
  Status status = AppendResult(trace.result(), &out);
  if (!status.ok()) return status;
  out.append(",");
  AppendLengths(trace, &out);
  out.append(",");
  AppendDt(trace, &out);
  out.append(",\"neutral_rate\":");
  AppendExact(options.neutral_rate, &out);
  out.append(",");
  status = AppendRadii(trace.body(), &out);
  if (!status.ok()) return status;
  out.append(",");
  status = AppendEdges("springs", trace.body().springs(), body_nodes, &out);
  if (!status.ok()) return status;
  out.append(",");
  status = AppendEdges("skin", trace.body().skin(), body_nodes, &out);
  if (!status.ok()) return status;
  if (trace.has_guidance()) {
    status = AppendGuidance(trace.guidance(), &out);
    if (!status.ok()) return status;
  }

  out.append(",\"frames\":[");
  bool first = true;
  for (int k = 0; k < trace.development_size(); ++k) {
    const v1::DevelopmentSnapshot& snapshot = trace.development(k);
    status =
        CheckSnapshot(k, snapshot, k > 0 ? &trace.development(k - 1) : nullptr);
    if (!status.ok()) return status;
    if (!first) out.append(",\n");
    first = false;
    out.append("{\"phase\":\"development\",\"step\":" +
               std::to_string(snapshot.step()) + ",\"x\":");
    AppendArray(snapshot.x(), &out);
    out.append(",\"y\":");
    AppendArray(snapshot.y(), &out);
    out.append(",\"r\":");
    AppendArray(snapshot.radius(), &out);
    out.append("}");
  }
  for (int k = 0; k < trace.frames_size(); ++k) {
    const v1::MotionFrame& frame = trace.frames(k);
    const v1::MotionFrame* previous = k > 0 ? &trace.frames(k - 1) : nullptr;
    status = CheckFrame(k, frame, previous, body_nodes);
    if (!status.ok()) return status;
    if (!first) out.append(",\n");
    first = false;
    out.append(std::string("{\"phase\":\"") + PhaseName(frame.phase()) +
               "\",\"step\":" + std::to_string(frame.step()) + ",\"x\":");
    AppendArray(frame.x(), &out);
    out.append(",\"y\":");
    AppendArray(frame.y(), &out);
    out.append(",\"act\":\"");
    for (const Actuation a :
         ClassifyActuation(previous, frame, options.neutral_rate)) {
      out.push_back(ActuationCode(a));
    }
    out.append("\"}");
  }
  out.append("]}");
  return out;
}

}  // namespace animat::viz
