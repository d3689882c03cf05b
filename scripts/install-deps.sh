#!/usr/bin/env bash
# Install the Debian packages certcyl needs. Idempotent: packages already present are skipped.
#   scripts/install-deps.sh            library, command, Python package and tests
#   scripts/install-deps.sh --study    also the peer libraries, plotting (experiments) and Chromium
#                                      (the test that renders the study's index.html)
#   scripts/install-deps.sh --paper    also LaTeX (the paper)
#   scripts/install-deps.sh --fuzz     also clang and its sanitizer/libFuzzer runtimes (scripts/fuzz.sh)
#   scripts/install-deps.sh --slurm    also Slurm and MUNGE (the batch scripts' test on a private local cluster)
set -euo pipefail

packages=(
  build-essential cmake ccache pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libmpfi-dev libeigen3-dev libqd-dev
  libboost-test-dev nlohmann-json3-dev libcli11-dev libbenchmark-dev libssl-dev
  pybind11-dev python3-dev python3-numpy
)
for arg in "$@"; do
  case "$arg" in
    --study) packages+=(libfcl-dev libbullet-dev libode-dev python3-matplotlib chromium) ;;
    --paper) packages+=(texlive-latex-recommended texlive-latex-extra latexmk poppler-utils) ;;
    --fuzz) packages+=(clang libclang-rt-14-dev) ;;
    --slurm) packages+=(slurm-wlm munge) ;;
    *) echo "install-deps.sh: unknown option '$arg' (expected --study, --paper, --fuzz or --slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
