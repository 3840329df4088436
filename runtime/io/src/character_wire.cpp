// Character <-> bytes (character_wire.hpp): sizes as 64-bit counts, vectors of plain values as raw memory.
#include "character_wire.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace cga::io_detail {

namespace {

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void count(std::size_t n) { value(std::uint64_t(n)); }
  void string(const std::string& s) {
    count(s.size());
    out_ += s;
  }
  template <class T>
  void values(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    count(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void strings(const std::vector<std::string>& v) {
    count(v.size());
    for (const std::string& s : v) string(s);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <class T>
  void value(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::memcpy(&v, take(sizeof v), sizeof v);
  }
  // A count of items of `item_size` bytes each that the remaining bytes can hold (so a corrupt count cannot
  // ask for a huge allocation).
  std::size_t count(std::size_t item_size) {
    std::uint64_t n = 0;
    value(n);
    if (item_size > 0 && n > (in_.size() - at_) / item_size) throw std::runtime_error("character data cut short");
    return std::size_t(n);
  }
  void string(std::string& s) {
    const std::size_t n = count(1);
    s.assign(take(n), n);
  }
  template <class T>
  void values(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    v.resize(count(sizeof(T)));
    if (!v.empty()) std::memcpy(v.data(), take(v.size() * sizeof(T)), v.size() * sizeof(T));
  }
  void strings(std::vector<std::string>& v) {
    v.resize(count(sizeof(std::uint64_t)));
    for (std::string& s : v) string(s);
  }
  bool at_end() const { return at_ == in_.size(); }

 private:
  const char* take(std::size_t n) {
    if (n > in_.size() - at_) throw std::runtime_error("character data cut short");
    const char* p = in_.data() + at_;
    at_ += n;
    return p;
  }
  std::string_view in_;
  std::size_t at_ = 0;
};

// One function per type for both directions, so that the two cannot disagree on the order of fields.
template <class IO, class C>
void fields(IO& io, C& ch) {
  io.string(ch.path);
  io.strings(ch.skeleton.names);
  io.values(ch.skeleton.parents);
  io.values(ch.skeleton.rest_local);
  io.strings(ch.warnings);
}

template <class IO, class M>
void fields_mesh(IO& io, M& m) {
  io.string(m.name);
  io.values(m.px), io.values(m.py), io.values(m.pz);
  io.values(m.nx), io.values(m.ny), io.values(m.nz);
  io.values(m.joints);
  io.values(m.weights);
  io.values(m.indices);
  io.values(m.joint_remap);
  io.values(m.inverse_bind_matrix);
  io.values(m.inverse_bind);
}

template <class IO, class K>
void fields_clip(IO& io, K& c) {
  io.string(c.name);
  io.value(c.duration);
  io.value(c.ticks_per_second);
}

template <class IO, class T>
void fields_track(IO& io, T& t) {
  io.values(t.translations);
  io.values(t.rotations);
  io.values(t.scales);
}

}  // namespace

std::string encode_character(const Character& ch) {
  Writer w;
  fields(w, ch);
  w.count(ch.meshes.size());
  for (const SkinnedMesh& m : ch.meshes) fields_mesh(w, m);
  w.count(ch.clips.size());
  for (const Clip& c : ch.clips) {
    fields_clip(w, c);
    w.count(c.tracks.size());
    for (const JointTrack& t : c.tracks) fields_track(w, t);
  }
  return w.take();
}

Character decode_character(std::string_view bytes) {
  Reader r(bytes);
  Character ch;
  fields(r, ch);
  ch.meshes.resize(r.count(sizeof(std::uint64_t)));
  for (SkinnedMesh& m : ch.meshes) fields_mesh(r, m);
  ch.clips.resize(r.count(sizeof(std::uint64_t)));
  for (Clip& c : ch.clips) {
    fields_clip(r, c);
    c.tracks.resize(r.count(3 * sizeof(std::uint64_t)));
    for (JointTrack& t : c.tracks) fields_track(r, t);
  }
  if (!r.at_end()) throw std::runtime_error("character data has trailing bytes");
  return ch;
}

}  // namespace cga::io_detail
