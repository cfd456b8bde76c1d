// The declared keys of `bolts:` and of a bolt's `from:` and `to:` (keys.hpp), one entry
// per key, in the order of docs/reference/scene-format.md. The ends' blocks, the law
// (the law registry's parameters) and the checks that tie keys together (a pretension
// within the yield force, axial_stiffness and the law's E1) stay in load_bolts.cpp.
#include "key_builders.hpp"
#include "rheodda/core/property_specs.hpp"

namespace rheodda::scene {

std::vector<EntryKey<BoltDescription>>& bolt_keys() {
  static std::vector<EntryKey<BoltDescription>> keys = [] {
    using E = BoltDescription;
    std::vector<EntryKey<E>> k;
    k.push_back(detail::field_key(
        KeyInfo{.map = "bolts", .name = "name", .type = KeyType::name, .unit = "–",
                .required = "the bolt's name in bolts.csv", .default_text = "required",
                .meaning = "unique; the bolt's `bolt` in bolts.csv"},
        &E::name));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "bolts", .name = "from", .type = KeyType::map, .unit = "–",
                .required = "the first end: {point: [x, y], block: NAME}", .default_text = "required",
                .meaning = "the first end, a point on a block (`block` may be left out as for the points above)"}));
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "bolts", .name = "to", .type = KeyType::map, .unit = "–",
                .required = "the second end: {point: [x, y], block: NAME} or {fixed: [x, y]}",
                .default_text = "required",
                .meaning = "the second end, `{point: [x, y], block: NAME}` on another block, or `{fixed: [x, y]}` "
                           "an anchor fixed in space"}));
    // The bolt's properties: each the key of its declaration (core/property_specs.hpp), read
    // into and from the core::BoltProperties a BoltDescription is.
    for (EntryKey<E>& p : detail::declared_keys_of<E>("bolts", core::bolt_specs())) k.push_back(std::move(p));
    detail::key_named(k, "axial_stiffness").default_text = "required, unless the law has E1 (then E1)";
    k.push_back(detail::reader_key<E>(
        KeyInfo{.map = "bolts", .name = "law", .type = KeyType::map, .unit = "–", .default_text = "none",
                .meaning = "the law's name and parameters, as a joint set's `law` (above): creep of the axial force "
                           "(relaxation); force is the bolt's axial force, displacement its elongation, so E1, E2 in "
                           "force/length and eta1, eta2 in force·time/length; its E1 is the bolt's spring "
                           "(`axial_stiffness` left out, or equal); a damage law is refused, and so are `unidentified`, "
                           "`tested_stress` and `tested_duration` (a joint set's law only)",
                .submap = "law"}));
    return k;
  }();
  return keys;
}

namespace {

/// `point:` and `block:` of a bolt's end: read by read_block_point (the point must lie on the block).
std::vector<EntryKey<BlockPoint>> end_keys(const std::string& map) {
  return {detail::reader_key<BlockPoint>(KeyInfo{.map = map, .name = "point", .type = KeyType::point,
                                                 .unit = "length", .required = "[x, y] [length]",
                                                 .default_text = "required",
                                                 .meaning = "`[x, y]`: the end, a point on a block"}),
          detail::reader_key<BlockPoint>(KeyInfo{.map = map, .name = "block", .type = KeyType::reference,
                                                 .unit = "–", .default_text = "the only block the point lies on",
                                                 .meaning = "the block the end is on"})};
}

}  // namespace

std::vector<EntryKey<BlockPoint>>& bolt_end_keys() {
  static std::vector<EntryKey<BlockPoint>> keys = end_keys("bolts.from");
  return keys;
}

std::vector<EntryKey<BlockPoint>>& bolt_to_keys() {
  static std::vector<EntryKey<BlockPoint>> keys = [] {
    std::vector<EntryKey<BlockPoint>> k = end_keys("bolts.to");
    k[0].required.clear();  // or `fixed`
    k[0].default_text = "one of point, fixed";
    k.push_back(detail::reader_key<BlockPoint>(
        KeyInfo{.map = "bolts.to", .name = "fixed", .type = KeyType::point, .unit = "length",
                .default_text = "one of point, fixed", .meaning = "`[x, y]`: an anchor fixed in space (no `block`)"}));
    return k;
  }();
  return keys;
}

}  // namespace rheodda::scene
