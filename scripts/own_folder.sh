# Sourced by the scripts that write a results folder: claim_folder SCRIPT OUT MARKER makes OUT
# (a new folder, or one this script made: it holds MARKER) and marks it; else exit 2. A script
# never writes into a folder it did not create, nor through a symbolic link.
claim_folder() {
  local script="$1" out="$2" marker="$3"
  if [ -L "$out" ]; then echo "$script: $out: a symbolic link; give a plain folder" >&2; exit 2; fi
  if [ -e "$out" ] && [ ! -e "$out/$marker" ]; then
    echo "$script: $out: exists and was not made by this script; give a new folder" >&2
    exit 2
  fi
  mkdir -p "$out"
  touch "$out/$marker"
}
