#include "kautham/core/OctomapEnvironment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>

namespace kautham::core {

namespace {

namespace fs = std::filesystem;

// OctoMap's OcTree: 16 levels below the root; keys count finest voxels from the centre.
constexpr int kTreeDepth = 16;
constexpr int kKeyOffset = 1 << (kTreeDepth - 1);
// Bounds on what is read, so a hostile file cannot exhaust the memory: octomap needs about
// 80 bytes per node.
constexpr std::uintmax_t kMaxFileBytes = 64u << 20;
constexpr std::size_t kMaxNodes = 4u << 20;

/// What the text header of an octree file says, and where its data starts.
struct Header {
  std::string id;
  unsigned size = 0;  ///< number of nodes, root included
  double resolution = 0.0;
  std::size_t dataOffset = 0;
};

class OctreeFile {
 public:
  OctreeFile(const fs::path& file, const SourceLocation& where) : file_(file), where_(where) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(where_, "octree '" + file_.string() + "': " + message);
  }

  std::string readBytes() const {
    std::error_code error;
    if (!fs::is_regular_file(file_, error)) fail("no such file");
    const std::uintmax_t bytes = fs::file_size(file_, error);
    if (error) fail("cannot read it: " + error.message());
    if (bytes > kMaxFileBytes)
      fail("the file has " + std::to_string(bytes) + " bytes; at most " +
           std::to_string(kMaxFileBytes) + " are read");
    std::ifstream in(file_, std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) fail("cannot read it");
    if (data.empty()) fail("the file is empty");
    return data;
  }

  /// Parses the header as OctoMap does (first line, then "id", "size", "res" up to "data").
  Header readHeader(const std::string& bytes, const std::string& firstLine) const {
    std::istringstream s(bytes);
    std::string line;
    std::getline(s, line);
    if (line.compare(0, firstLine.size(), firstLine) != 0)
      fail("not an OctoMap file: the first line should start with '" + firstLine + "'");
    Header header;
    bool data = false;
    auto skipLine = [&s] { s.ignore(std::numeric_limits<std::streamsize>::max(), '\n'); };
    std::string token;
    while (!data && s >> token) {
      if (token == "data") {
        data = true;
        skipLine();
      } else if (token == "id") {
        s >> header.id;
      } else if (token == "size") {
        s >> header.size;
      } else if (token == "res") {
        s >> header.resolution;
      } else {
        skipLine();  // comments and keywords OctoMap ignores too
      }
      if (s.fail()) fail("malformed header: the value of '" + token + "' is unreadable");
    }
    if (!data) fail("malformed header: no 'data' line");
    if (header.id.empty()) fail("malformed header: no 'id'");
    if (!(header.resolution >= 1e-6 && header.resolution <= 1e3))
      fail("malformed header: the resolution must be between 1e-6 and 1000 m");
    header.dataOffset = s.eof() ? bytes.size() : static_cast<std::size_t>(s.tellg());
    return header;
  }

  /// Walks the nodes of the data without building them: a truncated or corrupt tree is found
  /// here, before octomap reads it (it trusts its input). Returns the number of nodes.
  /// Binary (.bt) nodes: two bytes, two bits per child (00 unknown, 01 free, 10 occupied,
  /// 11 has children). Full (.ot) nodes: a float (log-odds), then one bit per existing child.
  std::size_t countNodes(const std::string& bytes, std::size_t offset, bool binary) const {
    std::size_t position = offset;
    std::size_t nodes = 1;
    walk(bytes, position, 0, binary, nodes);
    return nodes;
  }

 private:
  void walk(const std::string& bytes, std::size_t& position, int depth, bool binary,
            std::size_t& nodes) const {
    const std::size_t need = binary ? 2 : sizeof(float) + 1;
    if (bytes.size() - position < need) fail("corrupt or truncated data");
    if (!binary) position += sizeof(float);
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
    const unsigned children = binary ? byte(position) | (byte(position + 1) << 8) : byte(position);
    position += binary ? 2 : 1;
    for (int child = 0; child < 8; ++child) {
      const unsigned code = binary ? (children >> (2 * child)) & 3u : (children >> child) & 1u;
      if (code == 0) continue;
      if (++nodes > kMaxNodes)
        fail("more than " + std::to_string(kMaxNodes) + " nodes; coarsen the octree");
      const bool inner = binary ? code == 3 : true;
      if (!inner) continue;
      // A full node's child is always read as a node; a binary one only when it has children.
      if (depth + 1 > kTreeDepth || (binary && depth + 1 == kTreeDepth))
        fail("corrupt data: the tree is deeper than " + std::to_string(kTreeDepth) + " levels");
      walk(bytes, position, depth + 1, binary, nodes);
    }
  }

  fs::path file_;
  SourceLocation where_;
};

/// A box of whole finest voxels, in key units: [lo, hi) on each axis.
struct KeyBox {
  std::array<int, 3> lo;
  std::array<int, 3> hi;
};

/// Joins boxes that touch along `axis` and have the same extent on the two other axes.
void mergeAlong(std::vector<KeyBox>& boxes, int axis) {
  const int a = (axis + 1) % 3;
  const int b = (axis + 2) % 3;
  const auto key = [&](const KeyBox& k) {
    return std::make_tuple(k.lo[a], k.hi[a], k.lo[b], k.hi[b], k.lo[axis]);
  };
  std::sort(boxes.begin(), boxes.end(),
            [&](const KeyBox& p, const KeyBox& q) { return key(p) < key(q); });
  std::vector<KeyBox> merged;
  for (const KeyBox& box : boxes) {
    if (!merged.empty()) {
      KeyBox& last = merged.back();
      if (last.lo[a] == box.lo[a] && last.hi[a] == box.hi[a] && last.lo[b] == box.lo[b] &&
          last.hi[b] == box.hi[b] && last.hi[axis] == box.lo[axis]) {
        last.hi[axis] = box.hi[axis];
        continue;
      }
    }
    merged.push_back(box);
  }
  boxes.swap(merged);
}

/// Collects what is written to std::cerr while it lives.
class CaptureStandardError {
 public:
  CaptureStandardError() : saved_(std::cerr.rdbuf(captured_.rdbuf())) {}
  ~CaptureStandardError() { std::cerr.rdbuf(saved_); }
  CaptureStandardError(const CaptureStandardError&) = delete;
  CaptureStandardError& operator=(const CaptureStandardError&) = delete;
  std::string text() const { return captured_.str(); }

 private:
  std::ostringstream captured_;
  std::streambuf* saved_;
};

std::unique_ptr<octomap::OcTree> parseTree(const OctreeFile& octree, const std::string& bytes,
                                           bool binary) {
  // The first lines OctoMap writes (its constants for them are protected).
  const std::string firstLine = binary ? "# Octomap OcTree binary file" : "# Octomap OcTree file";
  const Header header = octree.readHeader(bytes, firstLine);
  if (header.id != "OcTree")
    octree.fail("holds a '" + header.id + "' tree; only an OcTree (occupancy) is supported");
  if (header.size == 0) octree.fail("the octree is empty: it has no occupied voxel");
  const std::size_t nodes = octree.countNodes(bytes, header.dataOffset, binary);
  if (nodes != header.size)
    octree.fail("corrupt data: the header announces " + std::to_string(header.size) +
                " nodes, the data holds " + std::to_string(nodes));

  std::istringstream in(bytes);
  const CaptureStandardError quiet;  // octomap reports progress on std::cerr
  if (binary) {
    auto tree = std::make_unique<octomap::OcTree>(header.resolution);
    if (!tree->readBinary(in)) octree.fail("octomap cannot read it: " + quiet.text());
    return tree;
  }
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(in));
  if (!tree) octree.fail("octomap cannot read it: " + quiet.text());
  auto* ocTree = dynamic_cast<octomap::OcTree*>(tree.get());
  if (!ocTree)
    octree.fail("holds a '" + tree->getTreeType() +
                "' tree; only an OcTree (occupancy) is supported");
  tree.release();
  return std::unique_ptr<octomap::OcTree>(ocTree);
}

}  // namespace

OctomapBoxes readOctomapBoxes(const fs::path& file, double occupancyThreshold,
                              const SourceLocation& where) {
  const OctreeFile octree(file, where);
  const std::string extension = file.extension().string();
  if (extension != ".bt" && extension != ".ot")
    octree.fail("unknown extension '" + extension + "'; expected .bt (binary) or .ot (full)");
  const std::string bytes = octree.readBytes();
  const std::unique_ptr<octomap::OcTree> tree = parseTree(octree, bytes, extension == ".bt");
  tree->setOccupancyThres(occupancyThreshold);

  OctomapBoxes result;
  result.resolution = tree->getResolution();
  std::vector<KeyBox> boxes;
  for (auto it = tree->begin_leafs(), end = tree->end_leafs(); it != end; ++it) {
    if (!tree->isNodeOccupied(*it)) continue;
    const int shift = kTreeDepth - static_cast<int>(it.getDepth());
    const octomap::OcTreeKey key = it.getKey();
    KeyBox box{};
    for (int i = 0; i < 3; ++i) {
      box.lo[i] = (static_cast<int>(key[i]) >> shift) << shift;
      box.hi[i] = box.lo[i] + (1 << shift);
    }
    boxes.push_back(box);
    result.occupiedVolume += std::pow(tree->getResolution() * (1 << shift), 3);
  }
  result.leaves = boxes.size();
  if (boxes.empty()) octree.fail("the octree is empty: it has no occupied voxel");
  std::size_t before = 0;
  while (before != boxes.size()) {  // until a round of the three axes joins nothing more
    before = boxes.size();
    for (int axis = 0; axis < 3; ++axis) mergeAlong(boxes, axis);
  }
  if (boxes.size() > kMaxEnvironmentBoxes)
    octree.fail(std::to_string(boxes.size()) + " boxes after merging its " +
                std::to_string(result.leaves) + " occupied leaves; at most " +
                std::to_string(kMaxEnvironmentBoxes) + " are simulated: coarsen the octree");
  const double res = result.resolution;
  for (const KeyBox& box : boxes) {
    Eigen::Vector3d lo, hi;
    for (int i = 0; i < 3; ++i) {
      lo[i] = (box.lo[i] - kKeyOffset) * res;
      hi[i] = (box.hi[i] - kKeyOffset) * res;
    }
    result.boxes.emplace_back(lo, hi);
  }
  return result;
}

ObjectInstance makeEnvironmentObject(const std::string& name, const fs::path& file,
                                     const OctomapBoxes& boxes, const Pose& home,
                                     const SourceLocation& where) {
  ObjectInstance object;
  object.name = name;
  object.urdf = file;
  object.home = home;
  object.where = where;
  object.role = ObjectRole::Fixed;
  object.environment = EnvironmentSource{file, boxes.resolution, boxes.leaves, boxes.boxes.size()};
  object.model.name = name;
  Link link;
  link.name = "occupied";
  for (const Eigen::AlignedBox3d& box : boxes.boxes) {
    CollisionShape shape{Box{box.sizes()}, Eigen::Isometry3d::Identity()};
    shape.origin.translation() = box.center();
    link.collisions.push_back(shape);
  }
  object.model.links.push_back(std::move(link));
  return object;
}

}  // namespace kautham::core
