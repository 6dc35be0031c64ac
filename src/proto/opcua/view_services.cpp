// Browse, BrowseNext and TranslateBrowsePathsToNodeIds over the address space (docs/opcua.md,
// Services; OPC 10000-4 §5.8).
#include <algorithm>

#include "proto/opcua/node_ids.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kForward = 0, kInverse = 1, kBoth = 2;
constexpr uint32_t kDecodingError = static_cast<uint32_t>(StatusCodeValue::BadDecodingError);
constexpr uint32_t bad(StatusCodeValue v) { return static_cast<uint32_t>(v); }

struct BrowseParams {
  uint32_t direction = kForward, referenceType = 0, nodeClassMask = 0;
  bool includeSubtypes = true;
};

bool matches(const AddressSpace& space, const Reference& r, const BrowseParams& p) {
  if (p.direction == kForward && !r.forward) return false;
  if (p.direction == kInverse && r.forward) return false;
  if (p.referenceType != 0 && !isReferenceSubtype(r.type, p.referenceType, p.includeSubtypes)) return false;
  const auto nodeClass = static_cast<uint32_t>(space.node(r.target).nodeClass);
  return p.nodeClassMask == 0 || (p.nodeClassMask & nodeClass) != 0;
}

void encodeReference(Writer& w, const AddressSpace& space, const Reference& r) {
  const Node& target = space.node(r.target);
  encode(w, NodeId::num(0, r.type));
  encode(w, r.forward);
  encode(w, ExpandedNodeId{target.id, "", 0});
  encode(w, target.browseName);
  encode(w, LocalizedText{"", target.displayName});
  w.u32(static_cast<uint32_t>(target.nodeClass));
  encode(w, ExpandedNodeId{NodeId::num(0, target.typeDefinition), "", 0});
}

// Appends one BrowseResult: the references of `node` from `first` on, at most `max` (0: all);
// a continuation point in the session if more remain.
void browseFrom(ServiceContext& ctx, uint32_t node, uint32_t first, uint32_t max, const BrowseParams& p, Writer& out) {
  const AddressSpace& space = ctx.core.space();
  const auto& refs = space.node(node).references;
  uint32_t taken = 0, next = first;
  for (; next < refs.size(); ++next) {
    if (!matches(space, refs[next], p)) continue;
    if (max != 0 && taken == max) break;
    ++taken;
  }
  // Past the last taken reference: is there another match?
  bool more = false;
  for (uint32_t i = next; i < refs.size() && !more; ++i) more = matches(space, refs[i], p);
  Session& s = *ctx.session;
  if (more && s.continuationPoints.size() >= ctx.core.config().maxContinuationPoints) {
    out.u32(bad(StatusCodeValue::BadNoContinuationPoints));
    out.nullString();
    out.i32(0);
    return;
  }
  out.u32(0);
  if (more) {
    ContinuationPoint cp{s.nextContinuationPoint++, node, next, max, p.direction, p.referenceType, p.nodeClassMask, 0, p.includeSubtypes};
    s.continuationPoints.push_back(cp);
    out.i32(4);
    out.u32(cp.id);
  } else {
    out.nullString();
  }
  out.i32(static_cast<int32_t>(taken));
  uint32_t written = 0;
  for (uint32_t i = first; i < refs.size() && written < taken; ++i) {
    if (!matches(space, refs[i], p)) continue;
    encodeReference(out, space, refs[i]);
    ++written;
  }
}

void browseError(Writer& out, uint32_t status) {
  out.u32(status);
  out.nullString();
  out.i32(0);
}

}  // namespace

uint32_t handleBrowse(ServiceContext& ctx, Reader& in, Writer& out) {
  NodeId viewId;
  DateTime viewTime;
  uint32_t viewVersion = 0, maxRefs = 0, count = 0;
  if (!decode(in, viewId) || !decode(in, viewTime) || !in.u32(viewVersion) || !in.u32(maxRefs) || !in.arrayLength(count, 10))
    return kDecodingError;
  if (!viewId.isNull()) return bad(StatusCodeValue::BadViewIdUnknown);
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  out.i32(static_cast<int32_t>(count));
  for (uint32_t i = 0; i < count; ++i) {
    NodeId id, refType;
    BrowseParams p;
    uint32_t resultMask = 0;
    if (!decode(in, id) || !in.u32(p.direction) || !decode(in, refType) || !decode(in, p.includeSubtypes) ||
        !in.u32(p.nodeClassMask) || !in.u32(resultMask))
      return kDecodingError;
    auto node = ctx.core.space().find(id);
    if (!node) browseError(out, bad(StatusCodeValue::BadNodeIdUnknown));
    else if (p.direction > kBoth) browseError(out, bad(StatusCodeValue::BadBrowseDirectionInvalid));
    else if (!refType.isNull() && (refType.ns != 0 || refType.kind != NodeId::Kind::Numeric))
      browseError(out, bad(StatusCodeValue::BadReferenceTypeIdInvalid));
    else {
      p.referenceType = refType.numeric;
      browseFrom(ctx, *node, 0, maxRefs, p, out);
    }
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleBrowseNext(ServiceContext& ctx, Reader& in, Writer& out) {
  bool release = false;
  uint32_t count = 0;
  if (!decode(in, release) || !in.arrayLength(count, 4)) return kDecodingError;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  out.i32(static_cast<int32_t>(count));
  auto& points = ctx.session->continuationPoints;
  for (uint32_t i = 0; i < count; ++i) {
    ByteString token;
    if (!decode(in, token)) return kDecodingError;
    uint32_t id = 0;
    if (token.bytes.size() == 4)
      for (int k = 3; k >= 0; --k) id = (id << 8) | static_cast<uint8_t>(token.bytes[static_cast<size_t>(k)]);
    auto it = std::find_if(points.begin(), points.end(), [id](const ContinuationPoint& c) { return c.id == id; });
    if (token.bytes.size() != 4 || it == points.end()) {
      browseError(out, bad(StatusCodeValue::BadContinuationPointInvalid));
      continue;
    }
    ContinuationPoint cp = *it;
    points.erase(it);
    if (release) {
      browseError(out, 0);
      continue;
    }
    BrowseParams p{cp.direction, cp.referenceType, cp.nodeClassMask, cp.includeSubtypes};
    browseFrom(ctx, cp.node, cp.nextReference, cp.maxReferences, p, out);
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleTranslateBrowsePathsToNodeIds(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t count = 0;
  if (!in.arrayLength(count, 5)) return kDecodingError;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  const AddressSpace& space = ctx.core.space();
  out.i32(static_cast<int32_t>(count));
  std::vector<uint32_t> current, next;
  for (uint32_t i = 0; i < count; ++i) {
    NodeId start;
    uint32_t elements = 0;
    if (!decode(in, start) || !in.arrayLength(elements, 9)) return kDecodingError;
    auto node = space.find(start);
    current.clear();
    if (node) current.push_back(*node);
    uint32_t status = node ? 0 : bad(StatusCodeValue::BadNodeIdUnknown);
    for (uint32_t e = 0; e < elements; ++e) {
      NodeId refType;
      bool inverse = false, subtypes = true;
      QualifiedName target;
      if (!decode(in, refType) || !decode(in, inverse) || !decode(in, subtypes) || !decode(in, target)) return kDecodingError;
      next.clear();
      BrowseParams p{inverse ? kInverse : kForward, refType.ns == 0 ? refType.numeric : 0, 0, subtypes};
      for (uint32_t n : current)
        for (const Reference& r : space.node(n).references)
          if (matches(space, r, p) && space.node(r.target).browseName == target) next.push_back(r.target);
      current.swap(next);
    }
    if (status == 0 && (current.empty() || elements == 0)) status = bad(StatusCodeValue::BadNoMatch);
    out.u32(status);
    if (status != 0) {
      out.i32(0);
      continue;
    }
    out.i32(static_cast<int32_t>(current.size()));
    for (uint32_t n : current) {
      encode(out, ExpandedNodeId{space.node(n).id, "", 0});
      out.u32(0xFFFFFFFF);  // RemainingPathIndex: the whole path was followed
    }
  }
  encodeNoDiagnostics(out);
  return 0;
}

}  // namespace virtcom::proto::opcua
