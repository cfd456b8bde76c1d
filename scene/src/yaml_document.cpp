// libyaml events into yaml-cpp nodes (yaml_document.hpp).
#include "yaml_document.hpp"

#include <yaml.h>

#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace rheodda::scene {
namespace {
struct NodeAccess {};
}  // namespace
}  // namespace rheodda::scene

// yaml-cpp has no public way to make a Node with a mark (the line and column of
// every error the loader reports) from nodes built outside its parser: the
// constructor that wraps a detail::node is private, and its friends include the
// class template as_if. This specialisation, for a tag type of this file only,
// is that friend.
template <>
struct YAML::as_if<rheodda::scene::NodeAccess, rheodda::scene::NodeAccess> {
  static YAML::Node wrap(YAML::detail::node& node, YAML::detail::shared_memory_holder memory) {
    return YAML::Node(node, std::move(memory));
  }
};

namespace rheodda::scene {
namespace {

constexpr std::size_t kMaxDepth = 2000;  // yaml-cpp's DepthGuard

/// The parser, released on every path.
struct Parser {
  yaml_parser_t p{};
  Parser() { yaml_parser_initialize(&p); }
  ~Parser() { yaml_parser_delete(&p); }
};
struct Event {
  yaml_event_t e{};
  ~Event() { yaml_event_delete(&e); }
};

YAML::Mark mark_of(const yaml_mark_t& m) {
  YAML::Mark k;
  k.pos = static_cast<int>(m.index);
  k.line = static_cast<int>(m.line);
  k.column = static_cast<int>(m.column);
  return k;
}

bool is_null(const yaml_event_t& e) {
  // yaml-cpp's IsNullString: a plain scalar "~", "null", "Null", "NULL" or empty.
  if (e.data.scalar.style != YAML_PLAIN_SCALAR_STYLE || e.data.scalar.tag != nullptr) return false;
  const std::string v(reinterpret_cast<const char*>(e.data.scalar.value), e.data.scalar.length);
  return v.empty() || v == "~" || v == "null" || v == "Null" || v == "NULL";
}

std::string tag_of(const yaml_char_t* tag, bool non_specific_quoted) {
  if (tag) return reinterpret_cast<const char*>(tag);
  return non_specific_quoted ? "!" : "?";  // yaml-cpp's non-specific tags
}

/// yaml-cpp's NodeBuilder (src/nodebuilder.cpp), fed by libyaml's events.
class Builder {
 public:
  Builder() : memory_(new YAML::detail::memory_holder) {}

  YAML::Node root() {
    if (!root_) return YAML::Node();
    return YAML::as_if<NodeAccess, NodeAccess>::wrap(*root_, memory_);
  }

  YAML::detail::node& push(const YAML::Mark& mark, const yaml_char_t* anchor) {
    YAML::detail::node& node = memory_->create_node();
    node.set_mark(mark);
    if (anchor) anchors_[reinterpret_cast<const char*>(anchor)] = &node;
    push(node);
    return node;
  }
  void push(YAML::detail::node& node) {
    const bool needs_key = !stack_.empty() && stack_.back()->type() == YAML::NodeType::Map && keys_.size() < map_depth_;
    stack_.push_back(&node);
    if (needs_key) keys_.emplace_back(&node, false);
  }
  void pop() {
    if (stack_.size() == 1) {
      root_ = stack_[0];
      stack_.pop_back();
      return;
    }
    YAML::detail::node& node = *stack_.back();
    stack_.pop_back();
    YAML::detail::node& collection = *stack_.back();
    if (collection.type() == YAML::NodeType::Sequence) {
      collection.push_back(node, memory_);
    } else {
      auto& key = keys_.back();
      if (key.second) {
        collection.insert(*key.first, node, memory_);
        keys_.pop_back();
      } else {
        key.second = true;
      }
    }
  }
  void begin_map() { ++map_depth_; }
  void end_map() { --map_depth_; }
  std::size_t depth() const { return stack_.size(); }
  YAML::detail::node* anchor(const std::string& name) const {
    const auto it = anchors_.find(name);
    return it == anchors_.end() ? nullptr : it->second;
  }

 private:
  YAML::detail::shared_memory_holder memory_;
  YAML::detail::node* root_ = nullptr;
  std::vector<YAML::detail::node*> stack_;
  std::vector<std::pair<YAML::detail::node*, bool>> keys_;  // a map's key, and whether its value came
  std::size_t map_depth_ = 0;
  std::map<std::string, YAML::detail::node*> anchors_;
};

}  // namespace

YAML::Node load_yaml_document(const std::string& text) {
  Parser parser;
  yaml_parser_set_input_string(&parser.p, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  yaml_parser_set_encoding(&parser.p, YAML_UTF8_ENCODING);
  Builder b;
  for (bool documents = false;;) {
    Event ev;
    if (!yaml_parser_parse(&parser.p, &ev.e)) {
      std::string problem = parser.p.problem ? parser.p.problem : "malformed YAML";
      if (parser.p.context) problem = std::string(parser.p.context) + ": " + problem;
      const yaml_mark_t& m = parser.p.problem ? parser.p.problem_mark : parser.p.mark;
      throw YamlSyntaxError(problem, static_cast<int>(m.line), static_cast<int>(m.column));
    }
    const yaml_event_t& e = ev.e;
    const YAML::Mark mark = mark_of(e.start_mark);
    switch (e.type) {
      case YAML_STREAM_END_EVENT: return b.root();
      case YAML_DOCUMENT_START_EVENT:
        if (documents) return b.root();  // yaml-cpp's Load reads the first document
        documents = true;
        break;
      case YAML_DOCUMENT_END_EVENT: return b.root();
      case YAML_ALIAS_EVENT: {
        const std::string name = reinterpret_cast<const char*>(e.data.alias.anchor);
        YAML::detail::node* node = b.anchor(name);
        if (!node) throw YamlSyntaxError("the alias *" + name + " names no anchor defined before it", mark.line, mark.column);
        b.push(*node);
        b.pop();
        break;
      }
      case YAML_SCALAR_EVENT: {
        YAML::detail::node& node = b.push(mark, e.data.scalar.anchor);
        if (is_null(e)) {
          node.set_null();
        } else {
          node.set_scalar(std::string(reinterpret_cast<const char*>(e.data.scalar.value), e.data.scalar.length));
          node.set_tag(tag_of(e.data.scalar.tag, e.data.scalar.style != YAML_PLAIN_SCALAR_STYLE));
        }
        b.pop();
        break;
      }
      case YAML_SEQUENCE_START_EVENT:
      case YAML_MAPPING_START_EVENT: {
        if (b.depth() >= kMaxDepth)
          throw YamlSyntaxError("nested deeper than 2000 levels", mark.line, mark.column);
        const bool map = e.type == YAML_MAPPING_START_EVENT;
        YAML::detail::node& node = b.push(mark, map ? e.data.mapping_start.anchor : e.data.sequence_start.anchor);
        node.set_tag(tag_of(map ? e.data.mapping_start.tag : e.data.sequence_start.tag, false));
        node.set_type(map ? YAML::NodeType::Map : YAML::NodeType::Sequence);
        const bool flow = map ? e.data.mapping_start.style == YAML_FLOW_MAPPING_STYLE
                              : e.data.sequence_start.style == YAML_FLOW_SEQUENCE_STYLE;
        node.set_style(flow ? YAML::EmitterStyle::Flow : YAML::EmitterStyle::Block);
        if (map) b.begin_map();
        break;
      }
      case YAML_SEQUENCE_END_EVENT: b.pop(); break;
      case YAML_MAPPING_END_EVENT:
        b.end_map();
        b.pop();
        break;
      default: break;  // stream start, no event
    }
  }
}

}  // namespace rheodda::scene
