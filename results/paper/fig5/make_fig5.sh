#!/bin/sh
# Reproduces the spirit of the paper's Fig. 5 on bunny10k_textured (9,999 faces): Cohen's texture
# deviation against the attribute deviation of the texture coordinates, for a simplified copy with
# low texture distortion (b) and the same copy with perturbed UVs on the ears (c).
# Run from the repository root: sh results/paper/fig5/make_fig5.sh [path/to/meshdev]
set -eu
M=${1:-build-vis/apps/meshdev}
A=../shared/data/textured/bunny10k_textured/bunny10k_textured.ply
O=results/paper/fig5
V=front,right,back
[ -f "$A" ] || { echo "skip: $A is absent"; exit 0; }
# (b) low distortion: OpenMesh quadric to 50 % (seam-safe wedge UVs); (c) its UVs shifted on the ears.
"$M" simplify "$A" $O/bunny_low.ply --method openmesh-quadric --ratio 0.5
python3 $O/perturb_uvs.py $O/bunny_low.ply $O/bunny_high.ply 0.08 0.05
# Numbers: geometry, texcoord (attribute deviation), texcoord_cohen (Cohen), texture colours.
for c in low high; do
  "$M" compare "$A" $O/bunny_$c.ply --attributes geometry,cohen,texture --direction forward \
    --json $O/compare_$c.json > $O/compare_$c.txt
done
# One colour range per measure, shared by (b) and (c): [0, larger forward p99]; the few larger
# values (folded UVs of the simplifier, see README.md) are clamped to red.
range() { python3 -c "import json,sys; print(max(json.load(open('$O/compare_'+c+'.json'))['directions']['forward']['stats']['$1']['p99'] for c in ('low','high')))"; }
for m in geometry texcoord texcoord_cohen texture_color_de76; do
  hi=$(range $m)
  for c in low high; do
    "$M" compare "$A" $O/bunny_$c.ply --attributes geometry,cohen,texture --direction forward -q \
      --color-by $m --range 0 "$hi" --colored $O/dev_${m}_$c.ply --colorbar $O/colorbar_$m.png
    "$M" render $O/dev_${m}_$c.ply --out $O/fig5_${m}_$c.png --views $V --size 320 \
      --legend --range 0 "$hi" --title "$m, A -> bunny_$c"
    rm $O/dev_${m}_$c.ply
  done
done
# (a)-(c): the textured meshes themselves.
"$M" render "$A" --out $O/fig5_a_original.png --views $V --size 320 --title "(a) original, 9,999 faces"
"$M" render $O/bunny_low.ply --out $O/fig5_b_low.png --views $V --size 320 --title "(b) simplified, low texture distortion"
"$M" render $O/bunny_high.ply --out $O/fig5_c_high.png --views $V --size 320 --title "(c) simplified, UVs shifted on the ears"
