// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

// The VRML 2.0 parser behind Soup_topology/IO/VRML.h. Include that header, not this one.

#ifndef SOUP_TOPOLOGY_INTERNAL_VRML_PARSER_H
#define SOUP_TOPOLOGY_INTERNAL_VRML_PARSER_H

#include <Soup_topology/IO/VRML.h>
#include <Soup_topology/internal/VRML_lexer.h>
#include <Soup_topology/internal/triangulate_polygon.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {
namespace VRML {

// The soup built by the parser, in plain doubles and indices; appended to the caller's ranges
// only once the whole file has been read.
struct Soup
{
  std::vector<double> xyz;
  std::vector<std::array<std::size_t, 3>> triangles;
};

// Row-major 3x4 affine map.
struct Affine
{
  double m[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  bool identity = true;

  static Affine translation(const double t[3])
  {
    Affine a;
    a.m[3] = t[0];
    a.m[7] = t[1];
    a.m[11] = t[2];
    a.identity = (t[0] == 0 && t[1] == 0 && t[2] == 0);
    return a;
  }

  static Affine scaling(const double s[3])
  {
    Affine a;
    a.m[0] = s[0];
    a.m[5] = s[1];
    a.m[10] = s[2];
    a.identity = (s[0] == 1 && s[1] == 1 && s[2] == 1);
    return a;
  }

  // rotation of `angle` radians around the axis (x, y, z); identity for a null axis or angle
  static Affine rotation(double x, double y, double z, double angle)
  {
    Affine a;
    const double len = std::sqrt(x * x + y * y + z * z);
    if(len == 0 || angle == 0 || !std::isfinite(len))
      return a;
    x /= len;
    y /= len;
    z /= len;
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    a.m[0] = t * x * x + c;     a.m[1] = t * x * y - s * z; a.m[2] = t * x * z + s * y;
    a.m[4] = t * x * y + s * z; a.m[5] = t * y * y + c;     a.m[6] = t * y * z - s * x;
    a.m[8] = t * x * z - s * y; a.m[9] = t * y * z + s * x; a.m[10] = t * z * z + c;
    a.identity = false;
    return a;
  }

  // this * b
  Affine operator*(const Affine& b) const
  {
    if(identity)
      return b;
    if(b.identity)
      return *this;
    Affine r;
    for(int i = 0; i < 3; ++i)
    {
      for(int j = 0; j < 4; ++j)
      {
        double v = m[4 * i] * b.m[j] + m[4 * i + 1] * b.m[4 + j] + m[4 * i + 2] * b.m[8 + j];
        if(j == 3)
          v += m[4 * i + 3];
        r.m[4 * i + j] = v;
      }
    }
    r.identity = false;
    return r;
  }

  double determinant() const
  {
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8])
         + m[2] * (m[4] * m[9] - m[5] * m[8]);
  }

  void apply(const double* p, double* out) const
  {
    out[0] = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3];
    out[1] = m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7];
    out[2] = m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11];
  }
};

enum class Node_kind { SKIPPED, GROUP, SHAPE, INDEXED_FACE_SET, COORDINATE };

struct Node
{
  Node_kind kind = Node_kind::SKIPPED;
  std::string_view type;            // the node's type name as written
  std::size_t line = 0;             // where the node starts
  // whether an instance adds anything to the output (a shape, or a count of geometry outside a
  // shape): the instantiation skips the others, which can be DAGs of astronomical size
  bool contributes = false;
  // GROUP
  Affine local;
  std::vector<std::size_t> children;
  // SHAPE
  std::size_t geometry = npos;
  // INDEXED_FACE_SET
  std::size_t coord = npos;
  std::vector<std::int32_t> coord_index;
  std::vector<std::pair<std::size_t, std::size_t>> index_lines; // (first position, line) at each line change
  bool ccw = true;
  std::size_t triangle_count = 0;         // triangles an instance gives (k - 2 per polygon of k >= 3)
  std::vector<std::uint32_t> used_points; // the points of coord that coordIndex names, in increasing order
  // COORDINATE
  std::vector<double> xyz;

  static constexpr std::size_t npos = std::size_t(-1);

  std::size_t line_of_index(std::size_t position) const
  {
    std::size_t result = line;
    for(const auto& entry : index_lines) // few entries: one per line of the coordIndex field
    {
      if(entry.first > position)
        break;
      result = entry.second;
    }
    return result;
  }
};

class Parser : private Lexer
{
  static constexpr std::size_t npos = Node::npos;
  static constexpr std::size_t max_depth = 1000;

public:
  Parser(const char* begin, const char* end, const std::string& name,
         const Soup_topology::IO::VRML_read_options& options,
         Soup_topology::IO::VRML_read_result& result, Soup& soup)
    : Lexer(begin, end, name), options_(options), result_(result), soup_(soup)
  {
    const std::size_t bytes = static_cast<std::size_t>(end - begin);
    using Options = Soup_topology::IO::VRML_read_options;
    instance_budget_ = options.instance_budget != 0 ? options.instance_budget
                                                    : Options::budget(std::size_t(1) << 20, 2, bytes);
    output_budget_ = options.output_budget != 0 ? options.output_budget
                                                : Options::budget(std::size_t(1) << 21, 8, bytes);
  }

  void run()
  {
    read_header();
    std::vector<std::size_t> roots;
    for(;;)
    {
      skip_space();
      if(p_ == end_)
        break;
      if(*p_ == '}' || *p_ == ']' || *p_ == '{' || *p_ == '[')
        fail(std::string("unbalanced '") + *p_ + "' at the top level", line_);
      const std::size_t line = line_;
      const std::string_view word = read_word("a node");
      if(skip_statement(word))
        continue;
      const std::size_t id = parse_node_statement(word, line, true);
      if(id != npos)
        roots.push_back(id);
    }
    for(std::size_t id : roots)
      instantiate(id);
    result_.number_of_points = soup_.xyz.size() / 3;
    result_.number_of_triangles = soup_.triangles.size();
  }

private:
  // ------------------------------------------------------------------ syntax

  // skips up to the bracket matching the one just consumed (`open`, at `open_line`), checking
  // that brackets nest; `DEF name Type` met inside registers `name` as a skipped node
  void skip_balanced(char open, std::size_t open_line)
  {
    std::vector<std::pair<char, std::size_t>> stack{{open, open_line}};
    while(!stack.empty())
    {
      skip_space();
      if(p_ == end_)
        fail_eof(stack.back().first == '{' ? "a node body" : "a bracketed list", stack.back().second);
      const char c = *p_;
      if(c == '{' || c == '[')
      {
        stack.emplace_back(c, line_);
        ++p_;
      }
      else if(c == '}' || c == ']')
      {
        const char expected = stack.back().first == '{' ? '}' : ']';
        if(c != expected)
          fail(std::string("unbalanced '") + c + "': '" + stack.back().first + "' opened at line "
                 + std::to_string(stack.back().second) + " is closed by '" + c + "'",
               line_);
        stack.pop_back();
        ++p_;
      }
      else if(c == '"')
        skip_string();
      else
      {
        const std::size_t line = line_;
        const std::string_view word = read_word("a word");
        if(word == "DEF")
        {
          const std::string_view name = read_word("a DEF name");
          const std::string_view type = peek_word();
          defs_[name] = new_node(Node_kind::SKIPPED, type.empty() ? name : type, line);
        }
      }
    }
  }

  void read_coord_index(Node& node)
  {
    auto note_line = [&]() {
      if(node.index_lines.empty() || node.index_lines.back().second != line_)
        node.index_lines.emplace_back(node.coord_index.size(), line_);
    };
    const std::size_t open_line = read_bracketed_list("coordIndex", [&](std::size_t list_line) {
      check_list_item(list_line);
      note_line();
      node.coord_index.push_back(read_int32("coordIndex"));
    });
    if(open_line == 0)
    {
      note_line();
      node.coord_index.push_back(read_int32("coordIndex"));
    }
  }

  // `ROUTE`, `PROTO` and `EXTERNPROTO` statements: skipped, counted; false for other words
  bool skip_statement(std::string_view word)
  {
    if(word == "ROUTE")
    {
      read_word("a ROUTE source");
      read_word("TO");
      read_word("a ROUTE destination");
    }
    else if(word == "PROTO")
    {
      const std::size_t line = line_;
      read_word("a PROTO name");
      expect('[', "a PROTO interface", line);
      skip_balanced('[', line_);
      expect('{', "a PROTO body", line);
      skip_balanced('{', line_);
    }
    else if(word == "EXTERNPROTO")
    {
      const std::size_t line = line_;
      read_word("an EXTERNPROTO name");
      expect('[', "an EXTERNPROTO interface", line);
      skip_balanced('[', line_);
      const char c = peek();
      if(c == '[')
      {
        ++p_;
        skip_balanced('[', line_);
      }
      else if(c == '"')
        skip_string();
      else
        fail("expected the URL of an EXTERNPROTO, found " + quote_here(), line_);
    }
    else
      return false;
    ++result_.skipped_nodes[std::string(word)];
    return true;
  }

  // ------------------------------------------------------------------ nodes

  std::size_t new_node(Node_kind kind, std::string_view type, std::size_t line)
  {
    nodes_.emplace_back();
    nodes_.back().kind = kind;
    nodes_.back().type = type;
    nodes_.back().line = line;
    return nodes_.size() - 1;
  }

  // a node statement whose first word (`DEF`, `USE`, `NULL` or a type name) was read at `line`
  std::size_t parse_node_statement(std::string_view word, std::size_t line, bool count_skipped)
  {
    if(word == "DEF")
    {
      const std::string_view name = read_word("a DEF name");
      const std::size_t type_line = line_;
      const std::string_view type = read_word("a node type after DEF");
      const std::size_t id = parse_node(type, type_line, count_skipped);
      defs_[name] = id;
      return id;
    }
    if(word == "USE")
    {
      const std::string_view name = read_word("a USE name");
      const auto it = defs_.find(name);
      if(it == defs_.end())
        fail("USE of the undefined name '" + std::string(name) + "'", line);
      if(count_skipped && nodes_[it->second].kind == Node_kind::SKIPPED)
        ++result_.skipped_nodes[std::string(nodes_[it->second].type)];
      return it->second;
    }
    if(word == "NULL")
      return npos;
    return parse_node(word, line, count_skipped);
  }

  std::size_t parse_node_statement(bool count_skipped, const char* what)
  {
    skip_space();
    const std::size_t word_line = line_;
    const std::string_view word = read_word(what);
    return parse_node_statement(word, word_line, count_skipped);
  }

  struct Depth_guard
  {
    std::size_t& depth;
    Depth_guard(std::size_t& d, const std::string& name, std::size_t line) : depth(d)
    {
      if(++depth > max_depth)
        throw Soup_topology::IO::Read_error(name + ":" + std::to_string(line) + ": nodes nested too deeply");
    }
    ~Depth_guard() { --depth; }
  };

  std::size_t parse_node(std::string_view type, std::size_t line, bool count_skipped)
  {
    Depth_guard guard(depth_, name_, line);
    if(starts_number(type[0]) || type == "TRUE" || type == "FALSE")
      fail("expected a node, found '" + std::string(type) + "'", line);
    expect('{', ("the body of " + std::string(type)).c_str(), line);
    const std::size_t open_line = line_;
    if(type == "Transform" || type == "Group" || type == "Anchor" || type == "Collision")
      return parse_group(type, line, type == "Transform");
    if(type == "Shape")
      return parse_shape(type, line);
    if(type == "IndexedFaceSet")
      return parse_indexed_face_set(type, line);
    if(type == "Coordinate")
      return parse_coordinate(type, line);
    skip_balanced('{', open_line);
    if(count_skipped)
      ++result_.skipped_nodes[std::string(type)];
    return new_node(Node_kind::SKIPPED, type, line);
  }

  // the fields of a node body up to its closing brace; `field(name)` reads the value of the
  // fields it knows and returns true, the others are skipped
  template <typename FieldReader>
  void parse_body(std::string_view type, std::size_t open_line, const FieldReader& field)
  {
    for(;;)
    {
      skip_space();
      if(p_ == end_)
        fail_eof(("the body of " + std::string(type)).c_str(), open_line);
      const char c = *p_;
      if(c == '}')
      {
        ++p_;
        return;
      }
      if(c == '{' || c == '[' || c == ']' || c == '"')
        fail(std::string("unexpected '") + c + "' in the body of " + std::string(type)
               + " (opened at line " + std::to_string(open_line) + "), expected a field name",
             line_);
      const std::string_view name = read_word("a field name");
      if(skip_statement(name))
        continue;
      if(!field(name))
        skip_field_value(name);
    }
  }

  // skips the value of an unknown field
  void skip_field_value(std::string_view field)
  {
    skip_space();
    if(p_ == end_)
      fail_eof(("the value of " + std::string(field)).c_str(), 0);
    const char c = *p_;
    if(c == '[')
    {
      ++p_;
      skip_balanced('[', line_);
      return;
    }
    if(c == '"')
    {
      skip_string();
      return;
    }
    if(c == '{' || c == '}' || c == ']')
      fail("missing value for the field '" + std::string(field) + "'", line_);
    const std::string_view w = peek_word();
    if(starts_number(w[0]) || w == "TRUE" || w == "FALSE")
    {
      // scalars: numbers, booleans (SFVec3f, SFRotation, SFBool, ...)
      for(;;)
      {
        const std::string_view next = peek_word();
        if(next.empty() || !(starts_number(next[0]) || next == "TRUE" || next == "FALSE"))
          return;
        p_ += next.size();
      }
    }
    // an SFNode value
    parse_node_statement(false, "a node");
  }

  // MFNode `children`: `[ node ... ]` or one node
  void parse_children(std::size_t id)
  {
    const std::size_t open_line = read_bracketed_list("children", [&](std::size_t list_line) {
      if(*p_ == '[' || *p_ == '{' || *p_ == '}' || *p_ == '"')
        fail("unexpected " + quote_here() + " in children (opened at line "
               + std::to_string(list_line) + ")",
             line_);
      const std::size_t line = line_;
      const std::string_view word = read_word("a node");
      if(skip_statement(word))
        return;
      const std::size_t child = parse_node_statement(word, line, true);
      if(child != npos)
        nodes_[id].children.push_back(child);
    });
    if(open_line != 0)
      return;
    const std::size_t child = parse_node_statement(true, "a node");
    if(child != npos)
      nodes_[id].children.push_back(child);
  }

  std::size_t parse_group(std::string_view type, std::size_t line, bool is_transform)
  {
    const std::size_t open_line = line_;
    const std::size_t id = new_node(Node_kind::GROUP, type, line);
    double translation[3] = {0, 0, 0}, center[3] = {0, 0, 0}, scale[3] = {1, 1, 1};
    double rotation[4] = {0, 0, 1, 0}, scale_orientation[4] = {0, 0, 1, 0};
    parse_body(type, open_line, [&](std::string_view f) {
      if(f == "children")
        parse_children(id);
      else if(!is_transform)
        return false;
      else if(f == "translation")
        read_sf_doubles(translation, 3, "translation");
      else if(f == "rotation")
        read_sf_doubles(rotation, 4, "rotation");
      else if(f == "scale")
        read_sf_doubles(scale, 3, "scale");
      else if(f == "scaleOrientation")
        read_sf_doubles(scale_orientation, 4, "scaleOrientation");
      else if(f == "center")
        read_sf_doubles(center, 3, "center");
      else
        return false;
      return true;
    });
    if(is_transform)
    {
      // T * C * R * SR * S * SR^-1 * C^-1
      const double minus_center[3] = {-center[0], -center[1], -center[2]};
      const Affine sr = Affine::rotation(scale_orientation[0], scale_orientation[1],
                                         scale_orientation[2], scale_orientation[3]);
      const Affine sr_inverse = Affine::rotation(scale_orientation[0], scale_orientation[1],
                                                 scale_orientation[2], -scale_orientation[3]);
      nodes_[id].local = Affine::translation(translation) * Affine::translation(center)
                       * Affine::rotation(rotation[0], rotation[1], rotation[2], rotation[3])
                       * sr * Affine::scaling(scale) * sr_inverse
                       * Affine::translation(minus_center);
    }
    for(std::size_t child : nodes_[id].children)
      nodes_[id].contributes = nodes_[id].contributes || nodes_[child].contributes;
    return id;
  }

  std::size_t parse_shape(std::string_view type, std::size_t line)
  {
    const std::size_t open_line = line_;
    const std::size_t id = new_node(Node_kind::SHAPE, type, line);
    parse_body(type, open_line, [&](std::string_view f) {
      if(f == "geometry")
      {
        const std::size_t g = parse_node_statement(true, "a geometry node");
        nodes_[id].geometry = g;
        return true;
      }
      if(f == "appearance")
      {
        parse_node_statement(true, "an appearance node");
        return true;
      }
      return false;
    });
    const std::size_t g = nodes_[id].geometry;
    nodes_[id].contributes = (g != npos && nodes_[g].kind == Node_kind::INDEXED_FACE_SET);
    return id;
  }

  std::size_t parse_indexed_face_set(std::string_view type, std::size_t line)
  {
    const std::size_t open_line = line_;
    const std::size_t id = new_node(Node_kind::INDEXED_FACE_SET, type, line);
    parse_body(type, open_line, [&](std::string_view f) {
      if(f == "coord")
      {
        const std::size_t c_line = line_;
        const std::size_t c = parse_node_statement(false, "a Coordinate node");
        if(c != npos && nodes_[c].kind != Node_kind::COORDINATE)
          fail("the coord of an IndexedFaceSet must be a Coordinate node, not "
                 + std::string(nodes_[c].type),
               c_line);
        nodes_[id].coord = c;
      }
      else if(f == "coordIndex")
        read_coord_index(nodes_[id]);
      else if(f == "ccw")
        nodes_[id].ccw = read_bool("ccw");
      else
        return false;
      return true;
    });
    // every index must name a point of the coord
    Node& node = nodes_[id];
    const std::int64_t n = node.coord == npos
                             ? 0 : static_cast<std::int64_t>(nodes_[node.coord].xyz.size() / 3);
    for(std::size_t i = 0; i < node.coord_index.size(); ++i)
    {
      const std::int32_t v = node.coord_index[i];
      if(v < -1 || v >= n)
        fail("coordIndex " + std::to_string(v) + " out of range: the coord has "
               + std::to_string(n) + " points",
             node.line_of_index(i));
    }
    // what an instance gives: the triangles, and the points named (an instance appends only
    // those, so that many small shapes sharing one large Coordinate stay small)
    std::size_t corners = 0;
    for(std::size_t i = 0; i <= node.coord_index.size(); ++i)
    {
      if(i == node.coord_index.size() || node.coord_index[i] == -1)
      {
        if(corners >= 3)
          node.triangle_count += corners - 2;
        corners = 0;
        continue;
      }
      ++corners;
      const std::size_t v = static_cast<std::size_t>(node.coord_index[i]);
      if(mark_.size() <= v)
        mark_.resize(v + 1, 0);
      if(mark_[v] != id + 1)
      {
        mark_[v] = id + 1;
        node.used_points.push_back(static_cast<std::uint32_t>(v));
      }
    }
    std::sort(node.used_points.begin(), node.used_points.end());
    node.contributes = true; // counted when it is instantiated outside a Shape
    return id;
  }

  std::size_t parse_coordinate(std::string_view type, std::size_t line)
  {
    const std::size_t open_line = line_;
    const std::size_t id = new_node(Node_kind::COORDINATE, type, line);
    parse_body(type, open_line, [&](std::string_view f) {
      if(f != "point")
        return false;
      read_mf_double(nodes_[id].xyz, 3, "point");
      return true;
    });
    nodes_[id].contributes = true; // counted when it is instantiated outside a Shape
    return id;
  }

  // ------------------------------------------------------------------ output

  // counts one more node instance; `line` is the node's
  void charge_instance(std::size_t line)
  {
    if(++instances_ > instance_budget_)
      fail("the DEF/USE instances expand to more than " + std::to_string(instance_budget_)
             + " node instances (the limit for a file of this size, VRML_read_options::instance_budget)",
           line);
  }

  // counts `amount` more points and triangles; `line` is the IndexedFaceSet's
  void charge_output(std::size_t amount, std::size_t line)
  {
    if(amount > output_budget_ - output_)
      fail("the DEF/USE instances expand to more than " + std::to_string(output_budget_)
             + " points and triangles (the limit for a file of this size, VRML_read_options::output_budget)",
           line);
    output_ += amount;
  }

  // instantiates the root node `root` and everything below it, depth first, with an explicit
  // stack: a chain of USEs may be as long as the file
  void instantiate(std::size_t root)
  {
    struct Frame
    {
      std::size_t node;
      std::size_t next_child;
      std::size_t transform; // in `transforms`: the transform of the node's children
      bool owns_transform;   // whether the frame pushed it (else it shares its parent's)
    };
    std::vector<Frame> stack;
    std::vector<Affine> transforms{Affine()}; // a stack too, shared by frames of the same transform
    auto enter = [&](std::size_t id, std::size_t parent) {
      const Node& node = nodes_[id];
      if(!node.contributes)
        return;
      charge_instance(node.line);
      switch(node.kind)
      {
      case Node_kind::GROUP:
        if(node.local.identity)
          stack.push_back(Frame{id, 0, parent, false});
        else
        {
          transforms.push_back(transforms[parent] * node.local);
          stack.push_back(Frame{id, 0, transforms.size() - 1, true});
        }
        break;
      case Node_kind::SHAPE:
        emit_indexed_face_set(nodes_[node.geometry], transforms[parent]);
        break;
      case Node_kind::INDEXED_FACE_SET:
      case Node_kind::COORDINATE:
        // geometry outside a Shape: not rendered, so not read
        ++result_.skipped_nodes[std::string(node.type) + " outside a Shape"];
        break;
      case Node_kind::SKIPPED:
        break;
      }
    };
    enter(root, 0);
    while(!stack.empty())
    {
      Frame& frame = stack.back();
      const std::vector<std::size_t>& children = nodes_[frame.node].children;
      if(frame.next_child == children.size())
      {
        if(frame.owns_transform)
          transforms.pop_back();
        stack.pop_back();
        continue;
      }
      const std::size_t child = children[frame.next_child++];
      enter(child, frame.transform); // may move `frame`: not used after
    }
  }

  void emit_indexed_face_set(const Node& ifs, const Affine& transform)
  {
    const std::size_t shape = result_.number_of_shapes++;
    const std::size_t base = soup_.xyz.size() / 3;
    static const std::vector<double> no_points;
    const std::vector<double>& xyz = ifs.coord == npos ? no_points : nodes_[ifs.coord].xyz;
    const std::vector<std::uint32_t>& used = ifs.used_points;
    charge_output(used.size() + ifs.triangle_count, ifs.line);

    // the points named by coordIndex, in their order in the Coordinate; local_ maps a point of
    // the Coordinate to its place after `base`
    if(local_.size() < xyz.size() / 3)
      local_.resize(xyz.size() / 3);
    const std::size_t old = soup_.xyz.size();
    soup_.xyz.resize(old + 3 * used.size());
    double* out = soup_.xyz.data() + old;
    for(std::size_t j = 0; j < used.size(); ++j, out += 3)
    {
      const std::size_t v = used[j];
      local_[v] = j;
      const double* p = &xyz[3 * v];
      if(transform.identity)
        std::copy(p, p + 3, out);
      else
      {
        transform.apply(p, out);
        if(!std::isfinite(out[0]) || !std::isfinite(out[1]) || !std::isfinite(out[2]))
          fail("point " + std::to_string(v) + " of the Coordinate of line "
                 + std::to_string(nodes_[ifs.coord].line)
                 + " overflows (is not finite) once transformed to world coordinates",
               ifs.line);
      }
    }
    const bool mirrored = !transform.identity && transform.determinant() < 0;
    if(mirrored)
      ++result_.number_of_mirrored_shapes;
    const bool flip = (!ifs.ccw) != (mirrored && !options_.keep_mirrored_orientation);

    const std::size_t first_triangle = soup_.triangles.size();
    const std::vector<std::int32_t>& index = ifs.coord_index;
    std::size_t begin = 0;
    while(begin < index.size())
    {
      std::size_t end = begin;
      while(end < index.size() && index[end] != -1)
        ++end;
      add_polygon(index.data() + begin, end - begin, base, xyz, flip); // "-1 -1": a short polygon
      begin = end + 1;
    }
    result_.triangle_shape_ids.insert(result_.triangle_shape_ids.end(),
                                      soup_.triangles.size() - first_triangle, shape);
  }

  void push_triangle(std::size_t a, std::size_t b, std::size_t c, bool flip)
  {
    if(flip)
      soup_.triangles.push_back({a, c, b});
    else
      soup_.triangles.push_back({a, b, c});
  }

  void add_polygon(const std::int32_t* poly, std::size_t k, std::size_t base,
                   const std::vector<double>& xyz, bool flip)
  {
    ++result_.number_of_polygons;
    if(k < 3)
    {
      ++result_.number_of_short_polygons;
      return;
    }
    auto at = [&](std::size_t i) { return base + local_[static_cast<std::size_t>(poly[i])]; };
    if(k == 3)
    {
      push_triangle(at(0), at(1), at(2), flip);
      return;
    }
    // project to the plane of the Newell normal, oriented so that the polygon turns
    // counterclockwise (in the Coordinate's own frame: an affine map keeps the triangulation valid)
    const Polygon_projection projection = project_polygon(
      k, [&](std::size_t i) { return &xyz[3 * static_cast<std::size_t>(poly[i])]; }, uv_);
    auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
      return (uv_[2 * b] - uv_[2 * a]) * (uv_[2 * c + 1] - uv_[2 * a + 1])
           - (uv_[2 * b + 1] - uv_[2 * a + 1]) * (uv_[2 * c] - uv_[2 * a]);
    };

    // convex: no right turn, and the edge directions sweep around once (at most two sign
    // changes of the u component)
    bool convex = !projection.degenerate();
    int sign_changes = 0, last_sign = 0;
    for(std::size_t i = 0; convex && i < k; ++i)
    {
      const std::size_t j = (i + 1) % k, l = (i + 2) % k;
      if(turn(i, j, l) < 0)
        convex = false;
      const double du = uv_[2 * j] - uv_[2 * i];
      const int s = (du > 0) - (du < 0);
      if(s != 0)
      {
        if(last_sign != 0 && s != last_sign)
          ++sign_changes;
        last_sign = s;
      }
    }
    if(convex && sign_changes > 2)
      convex = false; // counted cyclically, a simple convex polygon has at most 2 (+1 at wrap)
    if(projection.degenerate())
      convex = true; // degenerate (all corners collinear): nothing better than a fan

    if(!convex)
    {
      ++result_.number_of_non_convex_polygons;
      if(options_.non_convex_rule == Soup_topology::IO::Non_convex_polygon_rule::EAR_CLIPPING)
      {
        const std::size_t left = clipper_.clip(uv_, k, [&](std::size_t a, std::size_t b, std::size_t c) {
          push_triangle(at(a), at(b), at(c), flip);
        });
        if(left != 0)
          ++result_.number_of_ear_clipping_failures; // no ear left: the rest was fanned
        return;
      }
    }
    for(std::size_t i = 1; i + 1 < k; ++i)
      push_triangle(at(0), at(i), at(i + 1), flip);
  }

  std::size_t depth_ = 0;
  const Soup_topology::IO::VRML_read_options& options_;
  Soup_topology::IO::VRML_read_result& result_;
  Soup& soup_;
  std::vector<Node> nodes_;
  std::unordered_map<std::string_view, std::size_t> defs_;
  std::vector<double> uv_;
  Ear_clipper clipper_;
  std::vector<std::size_t> mark_;  // per point of a Coordinate: 1 + the last IndexedFaceSet that named it
  std::vector<std::size_t> local_; // per point of a Coordinate: its place among those appended
  std::size_t instance_budget_ = 0, instances_ = 0, output_budget_ = 0, output_ = 0;
};

} // namespace VRML
} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_VRML_PARSER_H
