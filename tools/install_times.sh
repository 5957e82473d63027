#!/usr/bin/env bash
# Times the two package sets of tools/setup.sh on a fresh Debian 12 system: a
# minimal bookworm made with debootstrap in DIR (default /var/tmp/mechkin-fresh),
# then, inside it, `apt-get install` of the main set (what the README's first
# command needs) and of the test set on top (what the second adds). Prints the
# download+install wall time of each. Needs root, debootstrap and the network to
# Debian's mirror; leaves DIR behind (remove it with rm -rf).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-/var/tmp/mechkin-fresh}"
mirror="${MECHKIN_MIRROR:-http://deb.debian.org/debian}"
if [ ! -x "$dir/usr/bin/apt-get" ]; then
  t0=$SECONDS
  debootstrap --variant=minbase bookworm "$dir" "$mirror" >/dev/null
  echo "debootstrap (not counted): $((SECONDS - t0)) s"
fi
cp /etc/resolv.conf "$dir/etc/resolv.conf"
in_root() { chroot "$dir" /usr/bin/env DEBIAN_FRONTEND=noninteractive "$@"; }
in_root apt-get update -qq
for set in main tests; do
  read -r -a pkgs <<<"$(bash "$here/tools/setup.sh" --print-packages "$set")"
  t0=$SECONDS
  in_root apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >/dev/null
  echo "$set packages (${#pkgs[@]}): $((SECONDS - t0)) s, $(du -sm "$dir" | cut -f1) MB installed system"
done
