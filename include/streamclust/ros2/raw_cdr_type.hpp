// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// A Cyclone DDS type whose samples are serialized CDR payloads, kept as
/// bytes: the encapsulation header and the body exactly as a ROS 2 node
/// sends them. Any ROS 2 message type travels through it by name
/// (`sensor_msgs::msg::dds_::PointCloud2_`) without generated code, so the
/// project's own CDR decoders read what arrives and its encoders write what
/// leaves (the approach rmw_cyclonedds takes with its own serdata). Keyless
/// and XCDR1 only, as ROS 2 topics are.
///
/// Readers take `RawCdrSample`s with dds_takecdr and read `bytes()`; writers
/// hand a payload to dds_writecdr through `make_raw_cdr_sample`. The
/// sample-based paths (dds_write, dds_take with typed samples) are not used
/// and not supported.
///
/// Thread-safety: a sample is immutable once made and reference-counted by
/// Cyclone; any thread may read it while it holds a reference.

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>
#include <dds/ddsi/q_radmin.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

namespace streamclust::ros2 {

/// One serialized message: Cyclone's serdata header, then the payload.
struct RawCdrSample : ddsi_serdata {
  /// The payload, padded with zeros to a multiple of 4 bytes (Cyclone may
  /// copy up to that boundary); `size` bytes are the message.
  std::vector<unsigned char> payload;
  std::size_t size = 0;

  const std::uint8_t* bytes() const noexcept { return payload.data(); }
};

namespace detail {

inline RawCdrSample* new_raw_sample(const ddsi_sertype* type, ddsi_serdata_kind kind, std::size_t size) {
  auto* d = new RawCdrSample();
  ddsi_serdata_init(d, type, kind);
  d->hash = type != nullptr ? type->serdata_basehash : 0u;  // keyless: every sample is the one instance
  d->size = size;
  d->payload.assign((size + 3u) & ~std::size_t{3}, 0);
  return d;
}

inline const RawCdrSample* raw(const ddsi_serdata* d) { return static_cast<const RawCdrSample*>(d); }

// serdata operations
inline bool raw_eqkey(const ddsi_serdata*, const ddsi_serdata*) { return true; }  // keyless
inline std::uint32_t raw_size(const ddsi_serdata* d) { return static_cast<std::uint32_t>(raw(d)->size); }

inline ddsi_serdata* raw_from_ser(const ddsi_sertype* type, ddsi_serdata_kind kind, const nn_rdata* fragchain,
                                  std::size_t size) {
  RawCdrSample* d = new_raw_sample(type, kind, size);
  // Fragments may overlap: each copies only the bytes beyond the previous one's end.
  std::uint32_t done = 0;
  for (const nn_rdata* f = fragchain; f != nullptr; f = f->nextfrag) {
    if (f->maxp1 <= done) continue;
    const unsigned char* src = NN_RMSG_PAYLOADOFF(f->rmsg, NN_RDATA_PAYLOAD_OFF(f));
    const std::uint32_t end = std::min<std::uint32_t>(f->maxp1, static_cast<std::uint32_t>(size));
    if (end > done) std::memcpy(d->payload.data() + done, src + (done - f->min), end - done);
    done = f->maxp1;
  }
  return d;
}

inline ddsi_serdata* raw_from_ser_iov(const ddsi_sertype* type, ddsi_serdata_kind kind, ddsrt_msg_iovlen_t niov,
                                      const ddsrt_iovec_t* iov, std::size_t size) {
  RawCdrSample* d = new_raw_sample(type, kind, size);
  std::size_t at = 0;
  for (ddsrt_msg_iovlen_t i = 0; i < niov && at < size; ++i) {
    const std::size_t n = std::min<std::size_t>(iov[i].iov_len, size - at);
    std::memcpy(d->payload.data() + at, iov[i].iov_base, n);
    at += n;
  }
  return d;
}

inline ddsi_serdata* raw_from_keyhash(const ddsi_sertype* type, const ddsi_keyhash*) {
  return new_raw_sample(type, SDK_KEY, 0);
}

/// The sample-based write path is not used: dds_write on a raw type fails.
inline ddsi_serdata* raw_from_sample(const ddsi_sertype*, ddsi_serdata_kind, const void*) { return nullptr; }

inline void raw_to_ser(const ddsi_serdata* d, std::size_t off, std::size_t sz, void* buf) {
  std::memcpy(buf, raw(d)->payload.data() + off, sz);
}

inline ddsi_serdata* raw_to_ser_ref(const ddsi_serdata* d, std::size_t off, std::size_t sz, ddsrt_iovec_t* ref) {
  ref->iov_base = const_cast<unsigned char*>(raw(d)->payload.data() + off);
  ref->iov_len = static_cast<ddsrt_iov_len_t>(sz);
  return ddsi_serdata_ref(d);
}

inline void raw_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t*) { ddsi_serdata_unref(d); }

/// Typed samples are not supported (dds_take with samples fails).
inline bool raw_to_sample(const ddsi_serdata*, void*, void**, void*) { return false; }

inline ddsi_serdata* raw_to_untyped(const ddsi_serdata* d) {
  RawCdrSample* u = new_raw_sample(d->type, SDK_KEY, 0);
  u->type = nullptr;
  return u;
}

inline bool raw_untyped_to_sample(const ddsi_sertype*, const ddsi_serdata*, void*, void**, void*) { return true; }

inline void raw_free(ddsi_serdata* d) { delete static_cast<RawCdrSample*>(d); }

inline std::size_t raw_print(const ddsi_sertype*, const ddsi_serdata* d, char* buf, std::size_t size) {
  const int n = std::snprintf(buf, size, "(CDR, %zu bytes)", raw(d)->size);
  return n < 0 ? 0 : static_cast<std::size_t>(n);
}

inline void raw_get_keyhash(const ddsi_serdata*, ddsi_keyhash* buf, bool) { std::memset(buf, 0, sizeof *buf); }

inline const ddsi_serdata_ops& raw_serdata_ops() {
  static const ddsi_serdata_ops ops = [] {
    ddsi_serdata_ops o{};
    o.eqkey = raw_eqkey;
    o.get_size = raw_size;
    o.from_ser = raw_from_ser;
    o.from_ser_iov = raw_from_ser_iov;
    o.from_keyhash = raw_from_keyhash;
    o.from_sample = raw_from_sample;
    o.to_ser = raw_to_ser;
    o.to_ser_ref = raw_to_ser_ref;
    o.to_ser_unref = raw_to_ser_unref;
    o.to_sample = raw_to_sample;
    o.to_untyped = raw_to_untyped;
    o.untyped_to_sample = raw_untyped_to_sample;
    o.free = raw_free;
    o.print = raw_print;
    o.get_keyhash = raw_get_keyhash;
    return o;  // shared-memory (iceoryx) operations stay null: that transport is not used
  }();
  return ops;
}

// sertype operations
inline void raw_type_free(ddsi_sertype* t) {
  ddsi_sertype_fini(t);
  delete t;
}
inline void raw_zero_samples(const ddsi_sertype*, void*, std::size_t) {}
inline void raw_realloc_samples(void** ptrs, const ddsi_sertype*, void*, std::size_t, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) ptrs[i] = nullptr;
}
inline void raw_free_samples(const ddsi_sertype*, void**, std::size_t, dds_free_op_t) {}
inline bool raw_type_equal(const ddsi_sertype*, const ddsi_sertype*) { return true; }  // the name decides
inline std::uint32_t raw_type_hash(const ddsi_sertype*) { return 0; }
inline std::size_t raw_serialized_size(const ddsi_sertype*, const void*) { return SIZE_MAX; }
inline bool raw_serialize_into(const ddsi_sertype*, const void*, void*, std::size_t) { return false; }

inline const ddsi_sertype_ops& raw_sertype_ops() {
  static const ddsi_sertype_ops ops = [] {
    ddsi_sertype_ops o{};
    o.version = ddsi_sertype_v0;
    o.free = raw_type_free;
    o.zero_samples = raw_zero_samples;
    o.realloc_samples = raw_realloc_samples;
    o.free_samples = raw_free_samples;
    o.equal = raw_type_equal;
    o.hash = raw_type_hash;
    o.get_serialized_size = raw_serialized_size;
    o.serialize_into = raw_serialize_into;
    return o;  // no XTypes type information: endpoints match by topic and type name, as ROS 2's do
  }();
  return ops;
}

}  // namespace detail

/// A new raw-CDR type named `dds_type_name` (`pkg::msg::dds_::T_`), owned
/// by the caller until dds_create_topic_sertype takes it.
inline ddsi_sertype* make_raw_cdr_type(const std::string& dds_type_name) {
  auto* t = new ddsi_sertype();
  ddsi_sertype_init(t, dds_type_name.c_str(), &detail::raw_sertype_ops(), &detail::raw_serdata_ops(), true);
  t->allowed_data_representation = DDS_DATA_REPRESENTATION_FLAG_XCDR1;
  return t;
}

/// A sample holding a copy of `payload` (encapsulation header included), for
/// dds_writecdr, which takes the reference.
inline ddsi_serdata* make_raw_cdr_sample(const ddsi_sertype* type, const std::uint8_t* payload, std::size_t size) {
  RawCdrSample* d = detail::new_raw_sample(type, SDK_DATA, size);
  if (size > 0) std::memcpy(d->payload.data(), payload, size);
  return d;
}

}  // namespace streamclust::ros2
