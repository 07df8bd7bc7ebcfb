#!/usr/bin/env bash
# Writes a batch of COUNT parts (default 120) into DIR: part-file variants of the bundled
# cylinder panel, cone frustum and square-to-round (other sizes), and the bundled meshes, in
# several quantities and materials, with the manifest DIR/parts.csv that names them all (paths
# relative to it: the folder can be moved or shared).
#
#   bench/batch/make_batch.sh DIR [COUNT=120]
#   flatcut batch --manifest DIR/parts.csv -o OUT --jobs 2
#
# Deterministic: the same COUNT gives the same files.
set -euo pipefail
dir=${1:?usage: make_batch.sh DIR [COUNT]}
count=${2:-120}
here=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$dir/parts" "$dir/meshes"
# Each material with its sheet thickness (mm; none for cloth): the fan-in nest groups by both.
materials=(steel aluminium "stainless steel" cotton)
thicknesses=(1.5 2 1 "")
meshes=(saddle cone_frustum cylinder_segment cone_ring)

cylinder() { # name radius height sweep
    printf 'name = "%s"\nunits = "mm"\ngrain = [0.0, 0.0, 1.0]\n\n[[surface]]\nkind = "cylinder"\nradius = %s\nheight = %s\nangles = [0.0, %s]\n' "$@"
}
cone() { # name bottom top height
    printf 'name = "%s"\nunits = "mm"\n\n[[surface]]\nkind = "cone"\nbottom_radius = %s\ntop_radius = %s\nheight = %s\n' "$@"
}
transition() { # name width diameter height
    printf 'name = "%s"\nunits = "mm"\n\n[[surface]]\nkind = "loft"\nbottom = { shape = "rectangle", width = %s, depth = %s }\ntop = { shape = "circle", diameter = %s, z = %s }\n' "$1" "$2" "$2" "$3" "$4"
}

{
    echo "input,name,quantity,material,thickness"
    for ((i = 0; i < count; i++)); do
        name=$(printf 'part-%03d' "$i")
        material=${materials[$((i % ${#materials[@]}))]}
        thickness=${thicknesses[$((i % ${#materials[@]}))]}
        quantity=$((1 + i % 3))
        case $((i % 5)) in
            0) cylinder "$name" $((100 + i)) $((150 + 2 * i)) $((60 + i % 90)) > "$dir/parts/$name.toml"
               input=parts/$name.toml ;;
            1) cone "$name" $((90 + i)) $((40 + i % 30)) $((60 + i % 50)) > "$dir/parts/$name.toml"
               input=parts/$name.toml ;;
            2) transition "$name" $((150 + i)) $((80 + i % 40)) $((100 + i % 60)) > "$dir/parts/$name.toml"
               input=parts/$name.toml ;;
            *) mesh=${meshes[$((i % ${#meshes[@]}))]}
               cp "$here/samples/$mesh.obj" "$dir/meshes/"
               input=meshes/$mesh.obj ;;
        esac
        echo "$input,$name,$quantity,$material,$thickness"
    done
} > "$dir/parts.csv"
echo "$count parts: $dir/parts.csv"
