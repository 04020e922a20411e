#!/usr/bin/env bash
# Renders the before/after thumbnails of docs/images (200x150, `render` at its defaults) with
# two deepvox binaries, through docs/images/look_thumbnails.py, and prints how much of each
# image is clipped to pure white.
#
#   scripts/make-look-thumbnails.sh BEFORE_DEEPVOX [AFTER_DEEPVOX] [--set looks|samples|shadows] [--size WxH]
#
# AFTER_DEEPVOX defaults to this tree's build/bin/deepvox. --set samples renders the stand-ins
# of the Khronos sample models TransmissionTest, GlassVaseFlowers, DamagedHelmet and Duck
# (docs/images/feature_standins.py) into docs/images/<model>-{before,after}.png; --set shadows
# the shadow stand-ins (textured glass pane, glass cube and BLEND quad on the
# ground, folded cloth under glass, opaque and translucent, glass over grey BLEND quads) the
# same way; --set looks (the default) the lamp,
# transmission, attenuation and bunny thumbnails.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -lt 1 || "$1" == -* ]]; then
  sed -n '2,14p' "$0" >&2
  exit 2
fi
before="$1"
shift
after="$root/build/bin/deepvox"
if [[ $# -gt 0 && "$1" != -* ]]; then
  after="$1"
  shift
fi
for binary in "$before" "$after"; do
  [[ -x "$binary" ]] || { echo "make-look-thumbnails.sh: $binary is not an executable" >&2; exit 2; }
done
exec python3 "$root/docs/images/look_thumbnails.py" "$before" "$after" "$@"
