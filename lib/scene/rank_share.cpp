#include "scene/rank_share.hpp"

#include "core/byte_stream.hpp"

namespace corofem {

RankShare make_rank_share(const SceneBody& whole, const std::vector<int>& scene_vertex,
                          RankPart part, const std::vector<Transfer>& transfers) {
  RankShare share;
  share.part = std::move(part);
  share.body = body_part(whole, share.part);
  const int begin = share.part.first_vertex, end = begin + share.part.owned_vertices;
  share.scene_vertex_index.assign(scene_vertex.begin() + begin, scene_vertex.begin() + end);
  for (std::size_t l = 0; l < transfers.size(); ++l)
    share.transfers.push_back(l == 0 ? rows_of(transfers[0], share.part.global_vertex)
                                     : transfers[l]);
  return share;
}

namespace {

/// The share's fields in one order, for the writer (Share = const RankShare) and the reader.
/// Eigen's force vector goes through a std::vector.
template <class Bytes, class Share>
void share_fields(Bytes& io, Share& share, std::vector<double>& force) {
  auto& p = share.part;
  io.vector(p.global_vertex);
  io.vector(p.global_tet);
  io.vector(p.owned_tet);
  for (auto* n :
       {&p.owned_vertices, &p.halo_vertices, &p.first_vertex, &p.global_vertices, &p.global_tets})
    io.value(*n);
  auto& m = share.body.mesh;
  io.vector(m.rest);
  io.vector(m.tets);
  io.vector(m.node_tags);
  io.vector(m.element_tags);
  io.text(m.source);
  io.vector(share.body.materials);
  io.vector(share.body.fixed_vertices);
  io.vector(force);
  io.vector(share.scene_vertex_index);
}

template <class Bytes, class T>
void transfer_fields(Bytes& io, T& t) {
  for (auto* n : {&t.coarse, &t.fine, &t.first_row}) io.value(*n);
  io.vector(t.p_start);
  io.vector(t.p_col);
  io.vector(t.p_weight);
  io.vector(t.r_start);
  io.vector(t.r_col);
  io.vector(t.r_weight);
}

}  // namespace

std::vector<char> pack_rank_share(const RankShare& share) {
  ByteWriter out;
  const Eigen::VectorXd& f = share.body.external_force;
  std::vector<double> force(f.data(), f.data() + f.size());
  share_fields(out, share, force);
  out.value<std::uint64_t>(share.transfers.size());
  for (const Transfer& t : share.transfers) transfer_fields(out, t);
  return std::move(out.bytes());
}

RankShare unpack_rank_share(const std::vector<char>& bytes) {
  ByteReader in(bytes, "a rank's part of the mesh");
  RankShare share;
  std::vector<double> force;
  share_fields(in, share, force);
  share.body.external_force =
      Eigen::Map<const Eigen::VectorXd>(force.data(), static_cast<Eigen::Index>(force.size()));
  std::uint64_t transfers = 0;
  in.value(transfers);
  share.transfers.resize(transfers <= bytes.size() ? transfers : 0);
  for (Transfer& t : share.transfers) transfer_fields(in, t);
  if (share.transfers.size() != transfers || !in.at_end())
    throw NumericalFault("a rank's part of the mesh: its bytes do not parse");
  return share;
}

}  // namespace corofem
