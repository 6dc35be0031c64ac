// Read and Write (docs/opcua.md, Services; OPC 10000-4 §5.10). Values of PLC variables are
// encoded straight from the published image; writes are queued for the next scan boundary.
#include "proto/opcua/node_ids.hpp"
#include "proto/opcua/plc_values.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kTimestampsSource = 0, kTimestampsServer = 1, kTimestampsBoth = 2, kTimestampsNeither = 3;
constexpr uint32_t kDecodingError = static_cast<uint32_t>(StatusCodeValue::BadDecodingError);
constexpr uint32_t bad(StatusCodeValue v) { return static_cast<uint32_t>(v); }

template <class T>
void scalarVariant(Writer& w, BuiltinType type, const T& value) {
  w.u8(static_cast<uint8_t>(type));
  encode(w, value);
}

// The ServerStatusDataType structure (OPC 10000-5 §12.10) as an ExtensionObject body.
void encodeServerStatus(Writer& w, const ServerCore& core) {
  w.u8(static_cast<uint8_t>(BuiltinType::ExtensionObject));
  encode(w, NodeId::num(0, ids::kServerStatusDataTypeBinary));
  w.u8(static_cast<uint8_t>(ExtensionObject::Body::Binary));
  const size_t lengthAt = w.size();
  w.i32(0);
  encode(w, core.startTime());
  encode(w, dateTimeNow());
  w.i32(0);  // State: Running
  w.string("urn:virtcom");    // BuildInfo.ProductUri
  w.string("virtcom");        // ManufacturerName
  w.string("virtcom soft PLC");  // ProductName
  w.string("1.0");            // SoftwareVersion
  w.string("0");              // BuildNumber
  encode(w, core.startTime());  // BuildDate
  w.u32(0);                   // SecondsTillShutdown
  encode(w, LocalizedText{});  // ShutdownReason
  w.put32(lengthAt, static_cast<uint32_t>(w.size() - lengthAt - 4));
}

}  // namespace

uint32_t encodeValueAttribute(Writer& w, const ServerCore& core, const Node& n) {
  if (n.nodeClass != NodeClass::Variable) return bad(StatusCodeValue::BadAttributeIdInvalid);
  switch (n.source) {
    case ValueSource::Fixed: encode(w, n.fixed); return 0;
    case ValueSource::Plc: encodePlcVariant(w, n.plc, core.snapshot()); return 0;
    case ValueSource::CurrentTime: scalarVariant(w, BuiltinType::DateTime, dateTimeNow()); return 0;
    case ValueSource::StartTime: scalarVariant(w, BuiltinType::DateTime, core.startTime()); return 0;
    case ValueSource::ServerState: scalarVariant(w, BuiltinType::Int32, int32_t{0}); return 0;
    case ValueSource::ServerStatus: encodeServerStatus(w, core); return 0;
  }
  return bad(StatusCodeValue::BadInternalError);
}

namespace {

// AccessLevel, or UserAccessLevel for a session that may do `user` (nullptr: AccessLevel).
uint8_t accessLevel(const Node& n, const UserAccess* user) {
  const bool writable = n.writable && (!user || *user == UserAccess::Write);
  return static_cast<uint8_t>(kAccessRead | (writable ? kAccessWrite : 0));
}

// Appends the Variant of one attribute, or returns a Bad status (nothing appended).
uint32_t encodeAttribute(Writer& w, const ServerCore& core, const Session& session, const Node& n, uint32_t attribute) {
  const bool variable = n.nodeClass == NodeClass::Variable;
  switch (attribute) {
    case kNodeIdAttr: scalarVariant(w, BuiltinType::NodeId, n.id); return 0;
    case kNodeClassAttr: scalarVariant(w, BuiltinType::Int32, static_cast<int32_t>(n.nodeClass)); return 0;
    case kBrowseNameAttr: scalarVariant(w, BuiltinType::QualifiedName, n.browseName); return 0;
    case kDisplayNameAttr: scalarVariant(w, BuiltinType::LocalizedText, LocalizedText{"", n.displayName}); return 0;
    case kDescriptionAttr: scalarVariant(w, BuiltinType::LocalizedText, LocalizedText{"", n.description}); return 0;
    case kWriteMaskAttr:
    case kUserWriteMaskAttr: scalarVariant(w, BuiltinType::UInt32, uint32_t{0}); return 0;
    case kEventNotifierAttr:
      if (n.nodeClass != NodeClass::Object) break;
      scalarVariant(w, BuiltinType::Byte, uint8_t{0});
      return 0;
    case kValueAttr: return encodeValueAttribute(w, core, n);
    default: break;
  }
  if (!variable) return bad(StatusCodeValue::BadAttributeIdInvalid);
  switch (attribute) {
    case kDataTypeAttr: scalarVariant(w, BuiltinType::NodeId, n.dataType); return 0;
    case kValueRankAttr: scalarVariant(w, BuiltinType::Int32, n.valueRank); return 0;
    case kArrayDimensionsAttr: {
      w.u8(static_cast<uint8_t>(BuiltinType::UInt32) | kVariantArray);
      const bool plcArray = n.source == ValueSource::Plc && n.plc.isArray;
      if (plcArray) {
        w.i32(static_cast<int32_t>(n.plc.dims.size()));
        for (uint32_t d : n.plc.dims) w.u32(d);
      } else {
        // Properties of rank 1 (NamespaceArray, ...) have a length only the value knows: 0.
        w.i32(n.valueRank > 0 ? n.valueRank : 0);
        for (int32_t i = 0; i < n.valueRank; ++i) w.u32(0);
      }
      return 0;
    }
    case kAccessLevelAttr: scalarVariant(w, BuiltinType::Byte, accessLevel(n, nullptr)); return 0;
    case kUserAccessLevelAttr: scalarVariant(w, BuiltinType::Byte, accessLevel(n, &session.access)); return 0;
    case kMinimumSamplingIntervalAttr: scalarVariant(w, BuiltinType::Double, 0.0); return 0;
    case kHistorizingAttr: scalarVariant(w, BuiltinType::Boolean, false); return 0;
    default: return bad(StatusCodeValue::BadAttributeIdInvalid);
  }
}

}  // namespace

uint32_t handleRead(ServiceContext& ctx, Reader& in, Writer& out) {
  double maxAge = 0;
  uint32_t timestamps = 0, count = 0;
  if (!decode(in, maxAge) || !in.u32(timestamps) || !in.arrayLength(count, 9)) return kDecodingError;
  if (maxAge < 0) return bad(StatusCodeValue::BadMaxAgeInvalid);
  if (timestamps > kTimestampsNeither) return bad(StatusCodeValue::BadTimestampsToReturnInvalid);
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  const DateTime now = dateTimeNow();
  out.i32(static_cast<int32_t>(count));
  for (uint32_t i = 0; i < count; ++i) {
    NodeId id;
    uint32_t attribute = 0;
    String indexRange;
    QualifiedName encoding;
    if (!decode(in, id) || !in.u32(attribute) || !decode(in, indexRange) || !decode(in, encoding)) return kDecodingError;
    const size_t at = out.size();
    auto node = ctx.core.space().find(id);
    uint32_t status = bad(StatusCodeValue::BadNodeIdUnknown);
    if (node && !indexRange.text.empty()) status = bad(StatusCodeValue::BadIndexRangeInvalid);
    else if (node && !encoding.name.empty()) status = bad(StatusCodeValue::BadDataEncodingInvalid);
    else if (node) {
      const bool value = attribute == kValueAttr;
      const bool source = value && (timestamps == kTimestampsSource || timestamps == kTimestampsBoth);
      const bool server = value && (timestamps == kTimestampsServer || timestamps == kTimestampsBoth);
      out.u8(static_cast<uint8_t>(kDataValueValue | (source ? kDataValueSourceTime : 0) | (server ? kDataValueServerTime : 0)));
      status = encodeAttribute(out, ctx.core, *ctx.session, ctx.core.space().node(*node), attribute);
      if (status == 0) {
        if (source) encode(out, now);
        if (server) encode(out, now);
        continue;
      }
    }
    out.buffer().resize(at);
    out.u8(kDataValueStatus);
    out.u32(status);
  }
  encodeNoDiagnostics(out);
  return 0;
}

uint32_t handleWrite(ServiceContext& ctx, Reader& in, Writer& out) {
  uint32_t count = 0;
  if (!in.arrayLength(count, 9)) return kDecodingError;
  if (count == 0) return bad(StatusCodeValue::BadNothingToDo);
  if (count > ctx.core.config().maxOperations) return bad(StatusCodeValue::BadTooManyOperations);
  out.i32(static_cast<int32_t>(count));
  std::vector<uint8_t> bytes;
  for (uint32_t i = 0; i < count; ++i) {
    NodeId id;
    uint32_t attribute = 0;
    String indexRange;
    DataValue value;
    if (!decode(in, id) || !in.u32(attribute) || !decode(in, indexRange) || !decode(in, value)) return kDecodingError;
    auto node = ctx.core.space().find(id);
    uint32_t status = 0;
    if (!node) status = bad(StatusCodeValue::BadNodeIdUnknown);
    else if (attribute != kValueAttr) status = bad(StatusCodeValue::BadNotWritable);
    else if (!indexRange.text.empty()) status = bad(StatusCodeValue::BadIndexRangeInvalid);
    else {
      const Node& n = ctx.core.space().node(*node);
      if (n.source != ValueSource::Plc || !n.writable) status = bad(StatusCodeValue::BadNotWritable);
      else if (ctx.session->access != UserAccess::Write) status = bad(StatusCodeValue::BadUserAccessDenied);
      else if (!value.hasValue) status = bad(StatusCodeValue::BadTypeMismatch);
      else if ((status = plcBytesOf(value.value, n.plc, bytes)) == 0) status = ctx.core.write(n.plc, bytes);
    }
    out.u32(status);
  }
  encodeNoDiagnostics(out);
  return 0;
}

}  // namespace virtcom::proto::opcua
