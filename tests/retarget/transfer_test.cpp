// transfer_rig: the rig carried onto the target's own vertices (issue 13), the dense registration,
// the landmarks file, and the self-made ground truth (the built-in face, remeshed). Slower cases
// (rotated decimetre copy, finer remesh, user landmarks) are in transfer_slow_test.cpp (label
// "slow").
#include "transfer_fixtures.hpp"

TEST(LipSurface, MatchesTheSamplerAtItsGridPoints) {
  const auto& face = fixtures().source;
  const auto& lips = face.rig.lips;
  for (int j = 0; j < lips.samples_across; ++j)
    for (int i = 0; i < lips.samples_around; i += 5) {
      const Eigen::Vector3d p =
          rt::lip_surface_point(lips, static_cast<double>(i) / lips.samples_around,
                                static_cast<double>(j) / (lips.samples_across - 1));
      const Eigen::Vector3d q =
          face.mesh.vertices.row(lips.first_vertex + j * lips.samples_around + i);
      EXPECT_LT((p - q).norm(), 1e-12) << i << "," << j;
    }
}

TEST(Registration, PullsAnEllipsoidOntoALargerOneAndHonoursLandmarks) {
  const fm::Mesh source = rt::test::ellipsoid(1.0, 1.2, 0.9, 16, 24);
  const fm::Mesh target = rt::test::ellipsoid(1.15, 1.3, 1.0, 30, 48, 0.05);
  // landmark: the top pole goes 0.05 higher than the target's top (the landmark wins locally)
  const std::vector<rt::RegistrationLandmark> lm = {{0, Eigen::Vector3d(0.0, 1.35, 0.0)}};
  const auto r = rt::register_nonrigid(source, {}, target, lm);
  EXPECT_GT(r.report.initial_rms, 0.08);
  EXPECT_LT(r.report.final_rms, 0.01);  // ~10x better; a point-to-point ICP leaves a little
  EXPECT_NEAR(r.vertices(0, 1), 1.35, 0.02);
  EXPECT_THROW(rt::register_nonrigid(source, std::vector<std::uint8_t>(3, 1), target),
               emoface::InvalidInput);
  EXPECT_THROW(rt::register_nonrigid(source, {}, target, {{999999, Eigen::Vector3d::Zero()}}),
               emoface::InvalidInput);
  rt::RegistrationOptions bad;
  bad.stiffness = {};
  EXPECT_THROW(bad.validate(), emoface::InvalidInput);
}

TEST(Transfer, OntoTheBuiltInFaceItselfReproducesEveryParameter) {
  const auto& f = fixtures();
  const auto& r = f.self_transfer();
  ASSERT_EQ(r.face.mesh.vertices.rows(), f.source.mesh.vertices.rows());
  EXPECT_EQ(r.face.mesh.faces, f.source.mesh.faces);
  EXPECT_FALSE(r.face.rig.lips.samples_in_mesh);
  EXPECT_GT(r.face.rig.lips.bound.size(), 300u);
  for (const auto& e : compare(f.source, f.source.mesh, r, Eigen::Matrix3d::Identity(), 1.0)) {
    EXPECT_LT(e.worst, 0.005 * e.largest) << e.name;
  }
  // landmarks: the same vertices
  EXPECT_EQ(r.face.rig.ibug68, f.source.rig.ibug68);
  // eyeballs found by the sphere fit, with the built-in radius
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(r.face.rig.eyes[static_cast<std::size_t>(e)].eyeball_vertices,
              f.source.rig.eyes[static_cast<std::size_t>(e)].eyeball_vertices);
    EXPECT_NEAR(r.face.rig.eyes[static_cast<std::size_t>(e)].radius,
                f.source.rig.eyes[static_cast<std::size_t>(e)].radius, 1e-9);
  }
}

TEST(Transfer, OntoARemeshedCopyReproducesTheBuiltInDeformation) {
  const auto& f = fixtures();
  const auto& r = f.remesh_transfer();
  std::size_t worst_over = 0;
  for (const auto& e : compare(f.source, f.remeshed, r, Eigen::Matrix3d::Identity(), 1.0)) {
    std::printf(
        "  %-34s largest %.2f mm  worst %.3f mm (%.1f %%)  over 3 %%: %zu of %ld vertices\n",
        e.name.c_str(), 1e3 * e.largest, 1e3 * e.worst, 100 * e.worst / e.largest, e.over,
        static_cast<long>(f.remeshed.vertices.rows()));
    // The issue's check at every vertex. Measured: 0 of 3,150 beyond 3 %, worst 2.4 % (funneler);
    // 9 before session 5, on the mouth rim: the strip's shares as weights and the border's jaw
    // weights taken from the nearest jaw vertex of the copy (docs/retarget.md).
    EXPECT_EQ(e.over, 0u) << e.name;
    EXPECT_LT(e.worst, 0.03 * e.largest) << e.name;
    worst_over = std::max(worst_over, e.over);
  }
  std::printf("  worst: %zu vertices beyond 3 %%\n", worst_over);
}

TEST(Transfer, SeparatePartsMove) {
  const auto& f = fixtures();
  // The remeshed face (eyeballs are separate spheres) plus a lower-teeth box inside the mouth,
  // named through a group, and an unnamed box behind the upper lip.
  fm::Mesh m = f.remeshed;
  const auto add_box = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
    const auto base = static_cast<int>(m.vertices.rows());
    m.vertices.conservativeResize(base + 8, 3);
    for (int i = 0; i < 8; ++i)
      m.vertices.row(base + i) =
          (c + Eigen::Vector3d((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(),
                               (i & 4 ? 1 : -1) * h.z()))
              .transpose();
    const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<int> faces;
    for (const auto& s : q) {
      const auto nf = m.faces.rows();
      m.faces.conservativeResize(nf + 2, 3);
      m.faces.row(nf) << base + s[0], base + s[1], base + s[2];
      m.faces.row(nf + 1) << base + s[0], base + s[2], base + s[3];
      faces.push_back(static_cast<int>(nf));
      faces.push_back(static_cast<int>(nf + 1));
    }
    return faces;
  };
  const double mouth_y = f.source.mesh.vertices(f.source.rig.ibug68[66], 1);
  fm::MeshGroup teeth;
  teeth.group = "lower_teeth";
  teeth.faces =
      add_box(Eigen::Vector3d(0.0, mouth_y - 0.006, 0.085), Eigen::Vector3d(0.012, 0.003, 0.003));
  const auto upper_faces =
      add_box(Eigen::Vector3d(0.0, mouth_y + 0.007, 0.085), Eigen::Vector3d(0.012, 0.003, 0.003));
  const auto r = rt::transfer_rig(f.source, m, {teeth}, quick_options());
  std::map<fm::PartKind, int> kinds;
  for (const auto& p : r.report.parts) ++kinds[p.kind];
  EXPECT_EQ(kinds[fm::PartKind::Head], 1);
  EXPECT_EQ(kinds[fm::PartKind::Eyeball], 2);
  // the built-in face has teeth of its own (two more parts); the added boxes are recognised
  auto kind_of = [&](int vertex) {
    for (const auto& p : r.face.rig.parts)
      if (std::binary_search(p.vertices.begin(), p.vertices.end(), vertex)) return p.kind;
    return fm::PartKind::Other;
  };
  EXPECT_EQ(kind_of(m.faces(teeth.faces.front(), 0)), fm::PartKind::LowerTeeth);  // by name
  EXPECT_EQ(kind_of(m.faces(upper_faces.front(), 0)), fm::PartKind::UpperTeeth);  // by position
  EXPECT_GE(kinds[fm::PartKind::LowerTeeth], 1);
  EXPECT_GE(kinds[fm::PartKind::UpperTeeth], 1);
  const ms::FaceSolver solver(r.face.mesh, r.face.rig);
  const auto n = solver.deform(std::map<std::string, double>{});
  // gaze: the eyeballs rotate about their centres, the head stays
  const auto g = solver.deform(std::map<std::string, double>{{"eye_gaze_yaw", 0.3}});
  for (int e = 0; e < 2; ++e) {
    const auto& eye = r.face.rig.eyes[static_cast<std::size_t>(e)];
    ASSERT_FALSE(eye.eyeball_vertices.empty());
    double moved = 0.0;
    for (int v : eye.eyeball_vertices) {
      moved = std::max(moved, (g.vertices.row(v) - n.vertices.row(v)).norm());
      EXPECT_NEAR((g.vertices.row(v).transpose() - eye.centre).norm(),
                  (n.vertices.row(v).transpose() - eye.centre).norm(), 1e-12);
    }
    EXPECT_GT(moved, 0.5 * eye.radius * 0.29);  // a 0.3 rad turn moves the front by ~0.3 r
  }
  double head_moved = 0.0;
  for (int v : r.face.rig.parts.front().vertices)
    head_moved = std::max(head_moved, (g.vertices.row(v) - n.vertices.row(v)).norm());
  EXPECT_EQ(head_moved, 0.0);
  // the jaw carries the lower teeth (weight 1: a rigid rotation about the pivot), not the upper
  // ones
  const auto j = solver.deform(std::map<std::string, double>{{"masseter", 1.0}});
  const double angle = r.face.rig.jaw.max_angle;
  const int lower = m.faces(teeth.faces.front(), 0), upper = m.faces(upper_faces.front(), 0);
  const Eigen::Vector3d q = n.vertices.row(lower).transpose() - r.face.rig.jaw.pivot;
  const Eigen::Vector3d want =
      r.face.rig.jaw.pivot + Eigen::Vector3d(q.x(),
                                             q.y() * std::cos(angle) - q.z() * std::sin(angle),
                                             q.y() * std::sin(angle) + q.z() * std::cos(angle));
  EXPECT_LT((j.vertices.row(lower).transpose() - want).norm(), 1e-12);
  EXPECT_EQ((j.vertices.row(upper) - n.vertices.row(upper)).norm(), 0.0);
}

namespace {
// the MakeHuman head (CC0) as shipped in data/face (the same file as ../shared/meshes)
const char* kMakeHuman = EMOFACE_SOURCE_DIR "/data/face/makehuman_head.obj";
}

TEST(Transfer, MakeHumanHeadOpensItsClosedMouthAndClosesItsLids) {
  if (!std::filesystem::exists(kMakeHuman)) GTEST_SKIP() << "data/face/makehuman_head.obj absent";
  const auto& f = fixtures();
  const fm::Mesh mh = fm::read_mesh(kMakeHuman);
  const auto r = rt::transfer_rig(f.source, mh, {}, quick_options());
  EXPECT_EQ(r.face.mesh.vertices.rows(), 4459);
  EXPECT_GT(r.report.mouth_bag, 100u);                     // the closed mouth's bag was found
  const double h = r.report.head_height * r.report.scale;  // rig frame
  const ms::FaceSolver solver(r.face.mesh, r.face.rig);
  const auto& ib = r.face.rig.ibug68;
  const auto n = solver.deform(std::map<std::string, double>{});
  const auto open = solver.deform(std::map<std::string, double>{{"masseter", 1.0}});
  auto gap = [&](const ms::Deformation& d, int a, int b) {
    return (d.vertices.row(ib[static_cast<std::size_t>(a)]) -
            d.vertices.row(ib[static_cast<std::size_t>(b)]))
        .norm();
  };
  // inner lip centres 62 (upper) and 66 (lower)
  const double closed_gap = gap(n, 62, 66), open_gap = gap(open, 62, 66);
  std::printf("  MakeHuman lip gap: %.2f %% -> %.2f %% of the head height\n", 100 * closed_gap / h,
              100 * open_gap / h);
  EXPECT_GT(open_gap - closed_gap, 0.06 * h);
  // the upper half of the bag stays, the lower half follows the jaw
  std::size_t bag_upper_moved = 0, bag_upper = 0;
  const double mouth_y = n.vertices(ib[62], 1);
  for (Eigen::Index v = 0; v < n.vertices.rows(); ++v) {
    if (r.face.rig.materials[static_cast<std::size_t>(v)] != fm::Material::MouthInterior ||
        n.vertices(v, 1) < mouth_y + 0.01)
      continue;
    ++bag_upper;
    if ((open.vertices.row(v) - n.vertices.row(v)).norm() > 0.01 * h) ++bag_upper_moved;
  }
  EXPECT_GT(bag_upper, 10u);
  EXPECT_LT(bag_upper_moved, bag_upper / 5);
  // The inner-lip points were placed on the head's own slit (the fit alone put the mouth a lip's
  // height too low), so both lips are bound to the lip surface: lip-bound vertices above and
  // below the slit, and no lip-coloured vertex beyond the slit's corners (the colour used to
  // bleed onto the cheeks there). Slit corners: the extreme x of the mouth-bag vertices. The
  // outer mouth corners (48, 54) go with the inner points (the fit put them 13 mm outside).
  EXPECT_EQ(r.report.mouth_slit_points, 10u);
  std::size_t above = 0, below = 0;
  const double slit_y = 0.5 * (n.vertices(ib[62], 1) + n.vertices(ib[66], 1));
  for (const auto& b : r.face.rig.lips.bound) {
    if (b.weight < 1.0) continue;
    if (n.vertices(b.vertex, 1) > slit_y + 0.001) ++above;
    if (n.vertices(b.vertex, 1) < slit_y - 0.001) ++below;
  }
  std::printf("  MakeHuman lip-bound vertices: %zu above the slit, %zu below\n", above, below);
  EXPECT_GT(above, 20u);
  EXPECT_GT(below, 20u);
  double bag_lo = 1e9, bag_hi = -1e9, lip_lo = 1e9, lip_hi = -1e9;
  for (Eigen::Index v = 0; v < n.vertices.rows(); ++v) {
    const auto m = r.face.rig.materials[static_cast<std::size_t>(v)];
    if (m == fm::Material::MouthInterior)
      bag_lo = std::min(bag_lo, n.vertices(v, 0)), bag_hi = std::max(bag_hi, n.vertices(v, 0));
    if (m == fm::Material::Lip)
      lip_lo = std::min(lip_lo, n.vertices(v, 0)), lip_hi = std::max(lip_hi, n.vertices(v, 0));
  }
  std::printf("  MakeHuman mouth: bag x [%.4f, %.4f], lip colour x [%.4f, %.4f] m\n", bag_lo,
              bag_hi, lip_lo, lip_hi);
  const double slack = 0.1 * (bag_hi - bag_lo);
  EXPECT_GT(lip_lo, bag_lo - slack);
  EXPECT_LT(lip_hi, bag_hi + slack);
  // blink: the upper lid margin (upper-lid vertices of weight ≥ 0.9) comes down to the lower lid's
  // margin (lower-lid vertices of weight ≥ 0.9): their mean heights, per eye
  const auto blink = solver.deform(
      std::map<std::string, double>{{"eye_blink_l", 1.0}, {"eye_blink_r", 1.0}});  // AU45
  for (const auto& eye : r.face.rig.eyes) {
    auto mean_y = [](const ms::Deformation& d, const std::vector<int>& ids,
                     const std::vector<double>& w) {
      double s = 0.0;
      int c = 0;
      for (std::size_t k = 0; k < ids.size(); ++k)
        if (w[k] >= 0.9) s += d.vertices(ids[k], 1), ++c;
      return c ? s / c : std::nan("");
    };
    const double before = mean_y(n, eye.upper_lid, eye.upper_lid_weights) -
                          mean_y(n, eye.lower_lid, eye.lower_lid_weights);
    const double after = mean_y(blink, eye.upper_lid, eye.upper_lid_weights) -
                         mean_y(blink, eye.lower_lid, eye.lower_lid_weights);
    std::printf("  MakeHuman lid margins apart: %.2f %% -> %.2f %% of the head height\n",
                100 * before / h, 100 * after / h);
    EXPECT_GT(before, 0.005 * h);
    EXPECT_LT(std::abs(after), 0.25 * before);
  }
}

// The eyelid checks of check_lids, printed; `strict`: the margins meet without crossing and the
// flips stay within `max_flipped`.
void expect_lids_close(const rt::TransferResult& r, const char* what, bool strict,
                       int max_flipped) {
  const LidCheck c = check_lids(r, six_emotions());
  for (int e = 0; e < 2; ++e) {
    const auto k = static_cast<std::size_t>(e);
    std::printf(
        "  %s eye %d (%s): margin gap %.2f %% -> blink %.2f %% (worst %.2f %%, crossing %.3f %%)"
        " -> AU7 %.2f %% (central min %.2f %%) of the head height\n",
        what, e, r.report.lid_method[k].c_str(), c.open[k], c.closed[k], c.worst_closed[k],
        c.worst_crossing[k], c.narrowed[k], c.narrowed_min[k]);
    EXPECT_LT(c.closed[k], 0.5 * c.open[k]) << what << " eye " << e;    // blink closes
    EXPECT_LT(c.narrowed[k], 0.8 * c.open[k]) << what << " eye " << e;  // AU7 narrows
    EXPECT_GT(c.narrowed_min[k], 0.0) << what << " eye " << e;          // but leaves it open
    if (!strict) continue;
    EXPECT_LT(c.worst_closed[k], 1.5) << what << " eye " << e;  // every margin point meets
    // its partner without passing below it (0.05 % of the head height: 0.1 mm)
    EXPECT_LE(c.worst_crossing[k], 0.05) << what << " eye " << e;
  }
  std::printf("  %s: %d eye-region triangles turned over (%s)\n", what, c.flipped,
              c.worst_case.c_str());
  EXPECT_LE(c.flipped, max_flipped) << what << ": " << c.worst_case;
}

TEST(Transfer, RemeshedCopyLidsClose) {
  // The copy keeps the built-in face's lid weights (they give its margin full weight; the copy
  // must reproduce the built-in deformation). The built-in lids have weight 1 up to the corners,
  // so at blink 1 its upper lid passes below the lower one there (hidden by the eyeball) and thin
  // corner triangles turn over: measured 4 % of the head height, 56 triangles; not asserted.
  const auto& r = fixtures().remesh_transfer();
  for (int e = 0; e < 2; ++e)
    EXPECT_EQ(r.report.lid_method[static_cast<std::size_t>(e)], "generic");
  expect_lids_close(r, "remeshed", false, 1000);
}

TEST(Transfer, MakeHumanLidsCloseWithoutCrossing) {
  if (!std::filesystem::exists(kMakeHuman)) GTEST_SKIP() << "data/face/makehuman_head.obj absent";
  const auto r =
      rt::transfer_rig(fixtures().source, fm::read_mesh(kMakeHuman), {}, quick_options());
  for (int e = 0; e < 2; ++e)  // the lids were rebuilt from the socket's crease
    EXPECT_EQ(r.report.lid_method[static_cast<std::size_t>(e)], "crease");
  // a face shaped unlike the built-in one: the refinement on the face would turn the frame by
  // 7.7° (measured) and is not applied (RetargetOptions::refine_max_degrees, 2°)
  EXPECT_FALSE(r.fit.alignment.report.refined);
  EXPECT_GT(r.fit.alignment.report.refine_angle_deg, 2.0);
  // Measured 126 turned-over triangles with round 4's expressions (blink 23: small fold triangles
  // at the margin; sadness 39 and happiness 37 on the lower lid, where the region cut-off moves the
  // cheek and not the lid; anger 12, surprise 13; 116 before round 4; docs/retarget.md). Before the
  // lids were rebuilt the margins tore open (picture). Session 7 (AU4 group 2×, zygomatics 1.3×):
  // 137 (sadness 45, happiness 37, anger 20).
  expect_lids_close(r, "MakeHuman", true, 140);
}

TEST(Transfer, BadInputGivesClearErrors) {
  const auto& f = fixtures();
  const auto o = quick_options();
  for (double bad : {-0.1, 30.5, std::nan("")}) {
    auto b = o;
    b.fit.refine_max_degrees = bad;
    EXPECT_THROW(rt::transfer_rig(f.source, f.remeshed, {}, b), emoface::InvalidInput) << bad;
  }
  fm::Mesh empty;
  empty.vertices = f.source.mesh.vertices;
  empty.faces.resize(0, 3);
  EXPECT_THROW(rt::transfer_rig(f.source, empty, {}, o), emoface::InvalidInput);
  fm::Mesh nan = f.remeshed;
  nan.vertices(5, 1) = std::nan("");
  try {
    rt::transfer_rig(f.source, nan, {}, o);
    ADD_FAILURE();
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 5"), std::string::npos) << e.what();
  }
  // two heads side by side
  fm::Mesh two = f.remeshed;
  const auto nv = two.vertices.rows(), nf = two.faces.rows();
  two.vertices.conservativeResize(2 * nv, 3);
  two.faces.conservativeResize(2 * nf, 3);
  two.vertices.bottomRows(nv) = f.remeshed.vertices.rowwise() + Eigen::RowVector3d(0.5, 0, 0);
  two.faces.bottomRows(nf) = f.remeshed.faces.array() + static_cast<int>(nv);
  try {
    rt::transfer_rig(f.source, two, {}, o);
    ADD_FAILURE();
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("several heads"), std::string::npos) << e.what();
  }
  // a non-manifold edge (three triangles on one edge)
  fm::Mesh nm = f.remeshed;
  const int a = nm.faces(0, 0), b = nm.faces(0, 1);
  nm.vertices.conservativeResize(nm.vertices.rows() + 1, 3);
  nm.vertices.row(nm.vertices.rows() - 1) << 0.3, 0.3, 0.3;
  nm.faces.conservativeResize(nm.faces.rows() + 1, 3);
  nm.faces.row(nm.faces.rows() - 1) << a, b, static_cast<int>(nm.vertices.rows() - 1);
  EXPECT_THROW(rt::transfer_rig(f.source, nm, {}, o), emoface::InvalidInput);
  // landmarks with wrong ids or counts
  rt::UserLandmarks lm;
  lm.points.resize(68);
  for (int k : {36, 39, 42, 45, 30})
    lm.points[static_cast<std::size_t>(k)] = {rt::UserLandmarkKind::Vertex, 10, {}};
  lm.points[30].vertex = static_cast<int>(f.remeshed.vertices.rows());  // one past the end
  try {
    rt::transfer_rig(f.source, f.remeshed, {}, o, lm);
    ADD_FAILURE();
  } catch (const emoface::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("point 30"), std::string::npos) << e.what();
  }
  lm.points.resize(67);
  EXPECT_THROW(rt::transfer_rig(f.source, f.remeshed, {}, o, lm), emoface::InvalidInput);
}

TEST(LandmarksFile, RoundTripAndBadInput) {
  rt::UserLandmarks lm;
  lm.points.resize(68);
  lm.points[3] = {rt::UserLandmarkKind::Vertex, 1234, {}};
  lm.points[30] = {rt::UserLandmarkKind::Point, -1, Eigen::Vector3d(0.1, -2.5e-3, 1.0 / 3.0)};
  const std::string text = rt::format_landmarks(lm);
  const auto back = rt::parse_landmarks(text, "x.json");
  ASSERT_EQ(back.points.size(), 68u);
  EXPECT_EQ(back.points[3].kind, rt::UserLandmarkKind::Vertex);
  EXPECT_EQ(back.points[3].vertex, 1234);
  EXPECT_EQ(back.points[30].kind, rt::UserLandmarkKind::Point);
  EXPECT_EQ(back.points[30].point, lm.points[30].point);  // bit for bit
  EXPECT_EQ(back.points[0].kind, rt::UserLandmarkKind::Missing);
  EXPECT_EQ(rt::format_landmarks(back), text);
  auto expect_error = [](const std::string& body, const std::string& where) {
    try {
      rt::parse_landmarks(body, "lm.json");
      ADD_FAILURE() << body;
    } catch (const emoface::FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("lm.json"), std::string::npos) << e.what();
    }
  };
  const std::string head =
      R"({"format": "emoface.landmarks", "version": "1.0", "scheme": "ibug68", "points": )";
  std::string nulls = "[";
  for (int k = 0; k < 67; ++k) nulls += "null, ";
  expect_error(head + nulls + "null, null]}", "/points");          // 69 entries
  expect_error(head + "[1, 2]}", "/points");                       // 2 entries
  expect_error(head + nulls + "-4]}", "/points/67");               // negative id
  expect_error(head + nulls + "1.5]}", "/points/67");              // not an integer
  expect_error(head + nulls + "[1, 2]]}", "/points/67");           // 2 coordinates
  expect_error(head + nulls + "[1, \"a\", 2]]}", "/points/67/1");  // not a number
  expect_error(head + nulls + "[1, 1e999, 2]]}", "overflow");  // infinite: refused by the parser
  expect_error(head + nulls + "\"nan\"]}", "/points/67");      // a string
  expect_error(
      R"({"format": "emoface.landmarks", "version": "2.0", "scheme": "ibug68", "points": []})",
      "version");
  expect_error(
      R"({"format": "emoface.landmarks", "version": "1.0", "scheme": "mediapipe", "points": []})",
      "/scheme");
  expect_error(head + nulls + "null], \"extra\": 1}", "/extra");
  expect_error(head + nulls + "null", "lm.json");  // truncated
  EXPECT_THROW(rt::read_landmarks("/nonexistent/lm.json"), emoface::IoError);
}

TEST(TransferReport, HasTheTransferSection) {
  const auto& r = fixtures().remesh_transfer();
  const std::string text = rt::format_transfer_report(r, false);
  for (const char* key :
       {"\"version\": \"1.4\"", "\"refine_angle_deg\"", "\"lids\"", "\"transfer\"", "\"residuals\"",
        "\"ibug68\"", "\"parts\"", "\"frame\"", "\"mouth_bag\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  EXPECT_EQ(text.find("\"seconds\""), std::string::npos);
  EXPECT_EQ(text, rt::format_transfer_report(r, false));
  // residuals: mean ≤ p95 ≤ max in every region; on a remesh of the built-in surface they are tiny
  for (const auto& rr : r.report.residuals) {
    EXPECT_LE(rr.mean, rr.p95 + 1e-15) << rr.region;
    EXPECT_LE(rr.p95, rr.max + 1e-15) << rr.region;
    EXPECT_LT(rr.max_percent, 0.5) << rr.region;
  }
}
