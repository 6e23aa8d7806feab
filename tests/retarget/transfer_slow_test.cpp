// transfer_rig, the slower cases: a rotated decimetre copy, the iBUG landmarks on a finer remesh,
// user landmarks (label "slow": a few seconds each).
#include <cstdlib>

#include "transfer_fixtures.hpp"

TEST(Transfer, RotatedDecimetreCopyKeepsItsFrameAndMoves) {
  const auto& f = fixtures();
  const Eigen::Matrix3d rot = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
  const double scale = 10.0;  // metres → decimetres
  fm::Mesh input = f.remeshed;
  for (Eigen::Index v = 0; v < input.vertices.rows(); ++v)
    input.vertices.row(v) =
        (scale * (rot * Eigen::Vector3d(f.remeshed.vertices.row(v))) + Eigen::Vector3d(1, 2, 3))
            .transpose();
  // With EMOFACE_TRANSFER_DEMO_DIR set, the input is also written there as remeshed_head.obj (the
  // remeshed head of the pictures in docs/retarget.md, scripts/transfer_pictures.sh).
  if (const char* dir = std::getenv("EMOFACE_TRANSFER_DEMO_DIR"))
    fm::write_mesh(std::string(dir) + "/remeshed_head.obj", input);
  const auto r = rt::transfer_rig(f.source, input, {}, quick_options());
  // the frame maps the file's own positions into the rig frame and back
  const auto& fr = r.face.rig.frame;
  EXPECT_NEAR(fr.scale, 1.0 / scale, 0.01 / scale);
  for (Eigen::Index v = 0; v < input.vertices.rows(); ++v) {
    EXPECT_LT(
        (fr.to_rig(input.vertices.row(v).transpose()) - r.face.mesh.vertices.row(v).transpose())
            .norm(),
        1e-12);
    EXPECT_LT(
        (fr.to_mesh(r.face.mesh.vertices.row(v).transpose()) - input.vertices.row(v).transpose())
            .norm(),
        1e-9);
  }
  // the recovered rotation is the inverse of the applied one (the alignment alone: ≈ 0.5° off;
  // refined on the face (RetargetOptions::refine_alignment): measured 0.005°)
  const Eigen::AngleAxisd residual(fr.rotation * rot);
  std::printf("  rotated copy: frame %.4f deg off, scale %.5f of the true\n",
              residual.angle() * 180.0 / 3.14159265358979323846, fr.scale * scale);
  EXPECT_LT(std::abs(residual.angle()), 0.05 * 3.14159265358979323846 / 180.0);
  std::size_t worst_over = 0;
  double worst_share = 0.0;
  for (const auto& e : compare(f.source, f.remeshed, r, rot, scale)) {
    if (e.over > 0) std::printf("    %-34s over 3 %%: %zu\n", e.name.c_str(), e.over);
    worst_over = std::max(worst_over, e.over);
    worst_share = std::max(worst_share, e.worst / e.largest);
  }
  std::printf("  rotated copy: worst %zu of %ld vertices beyond 3 %% (worst %.1f %%)\n", worst_over,
              static_cast<long>(input.vertices.rows()), 100 * worst_share);
  // The check at every vertex, as on the unrotated copy (transfer_test.cpp). Measured
  // (session 5): 0 of 3,150; 9 before (masseter: the mouth rim, docs/retarget.md), and 365 before
  // the frame was refined on the face: the alignment's ≈ 0.5° tilt moved the §3.2.1 detected
  // landmarks (highest y, highest z, extreme x), this short GA (6 generations) did not recover,
  // and the registration does not undo a tangential misplacement.
  EXPECT_EQ(worst_over, 0u);
}

// A tilt small enough for the alignment to snap it away (AlignOptions::snap_degrees 1.5: the
// axis-aligned frame, 0.6° off; the pitch search on E then takes back a part in 0.5° steps; 0.21°
// are left): the refinement on the face (TransferOptions::refine_frame, RetargetOptions::
// refine_alignment) recovers it; without it the rig keeps what the alignment left.
TEST(Transfer, RefinedFrameRecoversASmallTilt) {
  const auto& f = fixtures();
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.6 * 3.14159265358979323846 / 180.0,
                                                 Eigen::Vector3d(1.0, 0.3, 0.2).normalized())
                                   .toRotationMatrix();
  fm::Mesh input = f.remeshed;
  for (Eigen::Index v = 0; v < input.vertices.rows(); ++v)
    input.vertices.row(v) = (tilt * Eigen::Vector3d(f.remeshed.vertices.row(v))).transpose();
  auto degrees = [](const Eigen::Matrix3d& m) {
    return Eigen::AngleAxisd(m).angle() * 180.0 / 3.14159265358979323846;
  };
  rt::TransferOptions plain = quick_options();
  plain.refine_frame = false;
  const auto a = rt::transfer_rig(f.source, input, {}, plain);
  const auto b = rt::transfer_rig(f.source, input, {}, quick_options());
  const double before = degrees(a.face.rig.frame.rotation * tilt);
  const double after = degrees(b.face.rig.frame.rotation * tilt);
  const auto& ar = b.fit.alignment.report;
  std::printf(
      "  frame error: %.3f deg aligned, %.4f deg refined (refinement %.3f deg, scale %.5f, "
      "%zu points)\n",
      before, after, ar.refine_angle_deg, ar.refine_scale, ar.refine_points);
  EXPECT_FALSE(a.fit.alignment.report.refined);
  EXPECT_TRUE(ar.refined);
  EXPECT_GT(before, 0.15);  // measured 0.213°
  EXPECT_LT(after, 0.02);   // measured 0.0019°
  // measured 1.0013: the decimated copy's chords lie inside the built-in surface
  EXPECT_NEAR(b.face.rig.frame.scale, 1.0, 0.005);
  // the mesh in the rig frame is the input through the refined frame
  for (Eigen::Index v = 0; v < input.vertices.rows(); ++v)
    EXPECT_LT((b.face.rig.frame.to_rig(input.vertices.row(v).transpose()) -
               b.face.mesh.vertices.row(v).transpose())
                  .norm(),
              1e-12);
}

TEST(Transfer, LandsTheInnerIbugLandmarksOnAFinerRemesh) {
  const auto& f = fixtures();
  const fm::Mesh target = rt::decimate(fm::subdivide_midpoint(f.source.mesh), 0.35, true);
  const auto r = rt::transfer_rig(f.source, target, {}, quick_options());
  const double height = r.report.head_height;
  double worst = 0.0;
  for (int k = 17; k < 68; ++k) {
    const Eigen::Vector3d got =
        r.face.mesh.vertices.row(r.face.rig.ibug68[static_cast<std::size_t>(k)]);
    const Eigen::Vector3d want =
        f.source.mesh.vertices.row(f.source.rig.ibug68[static_cast<std::size_t>(k)]);
    worst = std::max(worst, (got - want).norm() / height);
  }
  std::printf("  inner iBUG landmarks: worst %.2f %% of the head height (%ld vertices)\n",
              100 * worst, static_cast<long>(target.vertices.rows()));
  EXPECT_LT(worst, 0.01);
  for (const auto& l : r.report.landmarks) {
    EXPECT_EQ(l.source, "fit");
    EXPECT_GE(l.confidence, 0.0);
    EXPECT_LE(l.confidence, 1.0);
  }
}

TEST(Transfer, UserLandmarksAreUsedAndReported) {
  const auto& f = fixtures();
  // the true iBUG points of the remeshed copy: its vertex nearest to each built-in landmark
  rt::UserLandmarks lm;
  lm.points.resize(68);
  for (int k = 0; k < 68; ++k) {
    const Eigen::Vector3d p =
        f.source.mesh.vertices.row(f.source.rig.ibug68[static_cast<std::size_t>(k)]);
    if (k % 2 == 0) {
      lm.points[static_cast<std::size_t>(k)].kind = rt::UserLandmarkKind::Point;
      lm.points[static_cast<std::size_t>(k)].point = p;
    }
  }
  const auto r = rt::transfer_rig(f.source, f.remeshed, {}, quick_options(), lm);
  EXPECT_TRUE(r.report.user_landmarks);
  // the even iBUG points given name 7 chapter-3 landmarks (8 chin, 30 nose tip, 36 and 42 eye
  // corners, 24 brow, 48 and 54 mouth corners; retarget_landmark_ibug): they replace the fit's,
  // and the rig's landmark of that name is the user's vertex
  std::vector<std::string> expected;
  for (const auto& [name, k] : rt::retarget_landmark_ibug())
    if (k % 2 == 0) expected.push_back(name);
  auto got = r.report.replaced_landmarks;
  std::sort(got.begin(), got.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(got, expected);
  for (const auto& [name, k] : rt::retarget_landmark_ibug()) {
    if (k % 2 != 0) continue;
    for (const auto& l : r.face.rig.retarget_landmarks)
      if (l.name == name)
        EXPECT_EQ(l.vertex, r.report.landmarks[static_cast<std::size_t>(k)].vertex) << name;
    for (std::size_t i = 0; i < r.fit.landmark_names.size(); ++i)
      if (r.fit.landmark_names[i] == name)
        EXPECT_LT((r.fit.target_landmarks.row(static_cast<Eigen::Index>(i)).transpose() -
                   r.face.rig.frame.to_rig(lm.points[static_cast<std::size_t>(k)].point))
                      .norm(),
                  1e-12)
            << name;
  }
  for (int k = 0; k < 68; ++k) {
    const auto& l = r.report.landmarks[static_cast<std::size_t>(k)];
    EXPECT_EQ(l.source, k % 2 == 0 ? "user" : "fit");
    if (k % 2 == 0) {
      EXPECT_EQ(l.confidence, 1.0);
      // the user's point snapped to the nearest vertex of the head component (input frame)
      double best = 1e300;
      for (int v : r.face.rig.parts.front().vertices)
        best = std::min(best, (f.remeshed.vertices.row(v).transpose() -
                               lm.points[static_cast<std::size_t>(k)].point)
                                  .squaredNorm());
      EXPECT_LT((f.remeshed.vertices.row(l.vertex).transpose() -
                 lm.points[static_cast<std::size_t>(k)].point)
                    .norm(),
                std::sqrt(best) + 1e-9);
    }
  }
}

// The MakeHuman head with the default options (as `retarget` runs it): its rebuilt lids close. With EMOFACE_TRANSFER_DEMO_DIR set, close-ups of the eyes (neutral, blink,
// AU7, anger, fear at 0.9) and of the mouth (neutral, fear), front and three-quarter, are written
// there (docs/retarget.md, scripts/transfer_pictures.sh).
TEST(Transfer, MakeHumanCloseUps) {
  const char* mh = EMOFACE_SOURCE_DIR "/data/face/makehuman_head.obj";  // as ../shared/meshes
  if (!std::filesystem::exists(mh)) GTEST_SKIP() << "data/face/makehuman_head.obj absent";
  const auto r = rt::transfer_rig(fixtures().source, fm::read_mesh(mh));
  const LidCheck c = check_lids(r, six_emotions());
  for (int e = 0; e < 2; ++e) {
    const auto k = static_cast<std::size_t>(e);
    std::printf("  eye %d (%s): gap %.2f %% -> blink %.2f %% (worst %.2f %%) -> AU7 %.2f %%\n", e,
                r.report.lid_method[k].c_str(), c.open[k], c.closed[k], c.worst_closed[k],
                c.narrowed[k]);
    // measured 1.61 % / 1.57 % worst and 0.15 % (0.35 mm) crossing at the outer corners with the
    // default fit (the short test fit of transfer_test.cpp: 0.62 % and 0.02 %)
    EXPECT_LT(c.worst_closed[k], 2.0);
    EXPECT_LE(c.worst_crossing[k], 0.2);
    EXPECT_GT(c.narrowed_min[k], 0.0);
  }
  const char* dir = std::getenv("EMOFACE_TRANSFER_DEMO_DIR");
  if (!dir) return;
  const auto& rig = r.face.rig;
  const ms::FaceSolver solver(r.face.mesh, rig);
  const auto emotions = six_emotions();
  const std::vector<std::map<std::string, double>> cases = {
      {},
      {{"eye_blink_l", 1.0}, {"eye_blink_r", 1.0}},
      {{"orbicularis_oculi_palpebralis_l", 1.0}, {"orbicularis_oculi_palpebralis_r", 1.0}},
      emotions[2],   // anger
      emotions[3]};  // fear
  const auto colors = fm::material_colors(rig, r.face.mesh);
  Eigen::Vector3d mouth = Eigen::Vector3d::Zero();
  for (const auto& p : rig.lips.control_points)
    mouth += p / static_cast<double>(rig.lips.control_points.size());
  auto sheet = [&](const Eigen::Vector3d& target, const std::vector<std::size_t>& which) {
    std::vector<emoface::core::Image> tiles;
    for (auto view : {fm::View::Front, fm::View::ThreeQuarter})
      for (std::size_t i : which) {
        const auto d = solver.deform(cases[i]);
        fm::RenderOptions ro;
        ro.view = view;
        ro.width = 300, ro.height = 170;
        ro.target = target;
        ro.distance = 0.3;
        ro.field_of_view = 0.2;
        tiles.push_back(fm::render(fm::Mesh{d.vertices, r.face.mesh.faces}, colors, d.crease, ro));
      }
    return emoface::core::tile(tiles, static_cast<int>(which.size()));
  };
  const Eigen::Vector3d eyes =
      0.5 * (rig.eyes[0].centre + rig.eyes[1].centre) + Eigen::Vector3d(0.0, 0.0, 0.02);
  emoface::core::write_png(std::string(dir) + "/makehuman_eyes.png", sheet(eyes, {0, 1, 2, 3, 4}));
  emoface::core::write_png(std::string(dir) + "/makehuman_mouth.png",
                           sheet(mouth + Eigen::Vector3d(0.0, 0.0, 0.01), {0, 4}));
}
