#!/usr/bin/env bash
# Fails if any built emoface library or app links GPL code (project rule: no GPL code linked into a
# library or app; LGPL only as a shared library):
#  - a NEEDED entry (direct) or a resolved dependency (ldd, transitive) of an executable or shared
#    library naming a GPL library: libespeak-ng (GPL-3.0; speech runs the espeak-ng program
#    instead, docs/channels.md), SuiteSparse's GPL parts — libcholmod (its Supernodal, MatrixOps and
#    Modify modules are GPL-2+), libspqr, libumfpack, librbio, the GPU modules —, and a few other
#    common GPL libraries (readline, GSL, FFTW, x264/x265/xvid, libpostproc, fuzzylite);
#  - a NEEDED libceres (Debian's Ceres library links CHOLMOD; emoface uses Ceres' header-only
#    TinySolver and Jets, cmake/EmofaceCeresHeaders.cmake);
#  - a static archive with undefined references to those libraries' symbols (cholmod_,
#    SuiteSparseQR, umfpack_, espeak_, …) or to the compiled Ceres library (ceres:: functions that
#    are not inline, e.g. ceres::Solve), which would pull them in at link time.
# Test programs and benchmarks (tests/) are not checked: fuzzylite (GPL-3.0) is a test-only oracle.
# Usage: check_no_gpl_link.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: check_no_gpl_link.sh BUILD_DIR}
# shared-object names (the part before .so) of GPL libraries
gpl_libs='libespeak-ng|libespeak|libcholmod|libspqr|libumfpack|librbio|libGPUQREngine'
gpl_libs+='|libSuiteSparse_GPURuntime|libreadline|libgsl|libfftw3[a-z_]*|libx264|libx265'
gpl_libs+='|libxvidcore|libpostproc|libfuzzylite[a-z-]*'
# symbol prefixes of those libraries (undefined references from a static archive)
gpl_symbols='cholmod_|SuiteSparseQR|spqr_|umfpack_|RBio|espeak_|espeak_ng_|readline$|rl_[a-z_]+$'
gpl_symbols+='|gsl_|fftw_|x264_|x265_|xvid_|pp_postprocess|fl::'
checked=0
bad=0
have_ldd=0
command -v ldd >/dev/null 2>&1 && have_ldd=1
while IFS= read -r -d '' f; do
  case "$f" in */CMakeFiles/*|*/_deps/*|*/install_test/*) continue ;; esac
  if [[ "$f" == *.a ]]; then
    checked=$((checked + 1))
    undefined=$(nm -u -C "$f" 2>/dev/null | awk '{ $1 = ""; sub(/^ /, ""); print }' | sort -u)
    hits=$(grep -E "^(${gpl_symbols})" <<<"$undefined" | head -3 || true)
    if [ -n "$hits" ]; then
      echo "static archive references GPL library symbols: $f: $(tr '\n' ' ' <<<"$hits")"; bad=1
    fi
    hits=$(grep -E '^ceres::' <<<"$undefined" | head -3 || true)
    if [ -n "$hits" ]; then
      echo "static archive references the compiled Ceres library (Debian's links CHOLMOD, GPL-2+;" \
        "use the header-only TinySolver/Jet): $f: $(tr '\n' ' ' <<<"$hits")"; bad=1
    fi
  elif readelf -h "$f" >/dev/null 2>&1; then
    checked=$((checked + 1))
    needed=$(readelf -d "$f" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
    for lib in $needed; do
      if grep -qE "^(${gpl_libs})\.so" <<<"$lib"; then
        echo "links GPL library $lib (NEEDED): $f"; bad=1
      elif grep -qE '^libceres\.so' <<<"$lib"; then
        echo "links the compiled Ceres library $lib (Debian's links CHOLMOD, GPL-2+): $f"; bad=1
      fi
    done
    if [ "$have_ldd" -eq 1 ]; then
      resolved=$(ldd "$f" 2>/dev/null | awk '{ print $1 }' | sed 's|.*/||' || true)
      for lib in $resolved; do
        if grep -qE "^(${gpl_libs})\.so" <<<"$lib" && ! grep -qxF "$lib" <<<"$needed"; then
          echo "links GPL library $lib indirectly (through a dependency; ldd): $f"; bad=1
        fi
      done
    fi
  fi
done < <(find "$build/libs" "$build/apps" -type f \( -name '*.a' -o -name '*.so*' -o -perm -u+x \) -print0 2>/dev/null)
if [ "$checked" -eq 0 ]; then echo "no libraries or apps found under $build"; exit 1; fi
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "checked $checked libraries and apps: none links a GPL library (espeak-ng, CHOLMOD, SPQR, …)" \
  "or the compiled Ceres library"
