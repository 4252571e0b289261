#!/usr/bin/env bash
# grtrace against GYOTO (Debian's gyoto 1.4.4: a peer to compare with, never a dependency of grtrace) on one
# matched scene: GYOTO's FixedStar, a uniform glowing and absorbing ball at rest near a Kerr hole, through GYOTO's
# own screen (tests/benchmarks/peers/gyoto_sphere.cpp gives grtrace the same rays). Each code is run at a few
# settings and once converged; every run's error is measured against its own code's converged run, the converged
# runs against each other, and the times per pixel are printed side by side, with a PNG of the images.
#
#   bash tests/benchmarks/peers/gyoto_compare.sh [SIZE=128] [THREADS=2] [OUT=build/gyoto-compare]
#
# Needs a release build (cmake --preset release); builds its target gyoto_sphere there. Installs gyoto-bin with apt
# when it is missing and this runs as root (else says how). Run it on an otherwise idle machine: it times both.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
size="${1:-128}"
threads="${2:-2}"
out="${3:-$root/build/gyoto-compare}"
build="${GRTRACE_BUILD:-$root/build/release}"

if ! [[ "$size" =~ ^[0-9]+$ ]] || ((size < 8 || size > 1024)); then
  echo "gyoto_compare.sh: SIZE must be a whole number of pixels, 8 .. 1024, got '$size'" >&2
  exit 2
fi
if ! [[ "$threads" =~ ^[0-9]+$ ]] || ((threads < 1)); then
  echo "gyoto_compare.sh: THREADS must be a whole number >= 1, got '$threads'" >&2
  exit 2
fi
if ! command -v gyoto > /dev/null; then
  if [[ $(id -u) -eq 0 ]]; then
    apt-get install -y --no-install-recommends gyoto-bin > /dev/null
  else
    echo "gyoto_compare.sh: GYOTO is not installed; as root: apt-get install gyoto-bin" >&2
    exit 2
  fi
fi
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  echo "gyoto_compare.sh: no build at $build; configure one first: cmake --preset release" >&2
  exit 2
fi
cmake --build "$build" --target gyoto_sphere > /dev/null
mkdir -p "$out"

# The scene (both programs): spin, observer, screen, ball.
spin=0.9 distance=1000 inclination=100 fov=0.03 ball_r=6 ball_theta=1.4 ball_phi=-0.3 ball_radius=2.5 opacity=0.3

# gyoto_xml NAME INTEGRATION DELTA_IN_OBJ: the scene with GYOTO's photon integration (its metric's own
# integrator, GYOTO's default, or a generic one) and its step inside the ball (DeltaInObj, GYOTO's default 0.05).
gyoto_xml() {
  local metric_integrator="" scenery_integrator=""
  if [[ "$2" != default ]]; then
    metric_integrator="<GenericIntegrator/>"
    scenery_integrator="<Integrator>runge_kutta_fehlberg78</Integrator><AbsTol>$2</AbsTol><RelTol>$2</RelTol>"
  fi
  cat > "$out/$1.xml" << EOF
<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<Scenery>
  <Metric kind="KerrBL"><Spin>$spin</Spin><Mass unit="sunmass">1</Mass>$metric_integrator</Metric>
  <Screen>
    <Distance unit="geometrical">$distance</Distance>
    <FieldOfView>$fov</FieldOfView>
    <Inclination unit="degree">$inclination</Inclination>
    <PALN>0</PALN><Argument>0</Argument>
    <Resolution>$size</Resolution>
    <AngleKind>Rectilinear</AngleKind>
    <ObserverKind>ZAMO</ObserverKind>
  </Screen>
  <Astrobj kind="FixedStar">
    <Position>$ball_r $ball_theta $ball_phi</Position>
    <Radius>$ball_radius</Radius>
    <NonRotating/>
    <IsotropicEmittedIntensity/>
    <Opacity kind="PowerLaw"><Exponent>0</Exponent><Constant>$opacity</Constant></Opacity>
    <OpticallyThin/>
    <DeltaInObj>$3</DeltaInObj>
  </Astrobj>
  <Quantities>Intensity</Quantities>
  $scenery_integrator
</Scenery>
EOF
}

runs="$out/runs.json"
echo "[" > "$runs"
first=1
record() {  # NAME CODE SECONDS
  [[ $first -eq 1 ]] || echo "," >> "$runs"
  first=0
  printf '{"name": "%s", "code": "%s", "fits": "%s", "seconds": %s, "threads": %s}' \
    "$1" "$2" "$out/$1.fits" "$3" "$threads" >> "$runs"
}
run_gyoto() {  # NAME INTEGRATION DELTA_IN_OBJ
  gyoto_xml "$1" "$2" "$3"
  rm -f "$out/$1.fits"
  local log seconds
  log="$(gyoto -T"$threads" "$out/$1.xml" "$out/$1.fits" 2>&1)"
  seconds="$(sed -n 's/.*Raytraced [0-9]* photons in \([0-9.e+-]*\)s.*/\1/p' <<< "$log" | tail -1)"
  if [[ -z "$seconds" || ! -f "$out/$1.fits" ]]; then
    echo "gyoto_compare.sh: gyoto failed on $1:" >&2
    echo "$log" | tail -5 >&2
    exit 1
  fi
  echo "gyoto $1: ${seconds} s" >&2
  record "$1" gyoto "$seconds"
}
run_grtrace() {  # NAME RTOL
  local line seconds
  line="$("$build/tests/benchmarks/gyoto_sphere" --out "$out/$1.fits" --size "$size" --threads "$threads" \
    --rtol "$2" --spin "$spin" --distance "$distance" --inclination "$inclination" --fov "$fov" \
    --ball "$ball_r,$ball_theta,$ball_phi" --ball-radius "$ball_radius" --opacity "$opacity")"
  seconds="$(sed -n 's/.*"seconds": \([0-9.e+-]*\),.*/\1/p' <<< "$line")"
  echo "grtrace $1: ${seconds} s" >&2
  record "$1" grtrace "$seconds"
}

# Each code's last run is its reference.
run_gyoto gyoto-default default 0.05
run_gyoto gyoto-rkf78-1e-8-in-0.005 1e-8 0.005
run_gyoto gyoto-converged 1e-12 0.0005
run_grtrace grtrace-rtol-1e-4 1e-4
run_grtrace grtrace-rtol-1e-6 1e-6
run_grtrace grtrace-rtol-1e-8 1e-8
run_grtrace grtrace-converged 1e-12
echo "]" >> "$runs"
echo "machine: $(nproc) cores, $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1); ${size}x${size}" \
  "pixels, $threads threads; gyoto $(gyoto --version 2>&1 | head -1)"
/usr/bin/python3 "$here/gyoto_compare.py" "$runs" "$out/gyoto-compare.png"
