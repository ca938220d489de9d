# Shared start of the benchmark scripts (frame_table.sh, visibility_ab.sh, light_scaling.sh):
# sourced, not run. bench_setup NAME: the repository root as working directory, Mesa's shader
# cache under build/, `lantern` (refused unless built) and `out`, a scratch directory removed at
# exit. bench_options NAME KEY... -- ARGS...: each `--KEY VALUE` of ARGS sets the variable KEY
# (declared by the script with its default); `--set VALUE` appends to the array `sets` when `set`
# is one of the KEYs; anything else, or a KEY without its value, exits 2 naming it.

bench_setup() {
  cd "$(dirname "${BASH_SOURCE[0]}")/.."
  export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$PWD/build/mesa-shader-cache}"
  lantern=build/bin/lantern
  [ -x "$lantern" ] || { echo "$1: build first (bash scripts/build.sh)" >&2; exit 2; }
  out=$(mktemp -d "/tmp/$1.XXXXXX")
  trap 'rm -rf "$out"' EXIT
}

bench_options() {
  local name=$1 keys=" "
  shift
  while [ $# -gt 0 ] && [ "$1" != -- ]; do keys+="$1 "; shift; done
  shift
  while [ $# -gt 0 ]; do
    local key=${1#--}
    if [ "$key" = "$1" ] || [[ "$keys" != *" $key "* ]]; then
      echo "$name: unknown argument '$1' (see the usage line in scripts/$name.sh)" >&2
      exit 2
    fi
    [ $# -ge 2 ] || { echo "$name: $1 needs a value" >&2; exit 2; }
    if [ "$key" = set ]; then sets+=(--set "$2"); else printf -v "$key" '%s' "$2"; fi
    shift 2
  done
}
