# Sourced by submit.sh and fit_submit.sh (not run): the argument checks of "INPUT OUT TASKS
# [sbatch options...]" and the submission of a job array followed by one job that starts once
# every task of the array succeeded (--dependency=afterok).

# check_submit_args NAME "$@": exits 2 with one line unless INPUT is a file, OUT not a symbolic
# link (refused as asperity's --out refuses one) and TASKS a whole number in [1, 99999]; sets
# input, out (absolute, links on its way kept as given, as asperity reads it), tasks, asperity
# (absolute: $ASPERITY or the project's build/asperity) and sbatch_options (the rest).
check_submit_args() {
  local name=$1
  shift
  if [ $# -lt 3 ]; then
    echo "usage: $0 $name.yaml OUT TASKS [sbatch options...]" >&2
    exit 2
  fi
  input=$1 out=$2 tasks=$3
  shift 3
  sbatch_options=("$@")
  if ! [[ $tasks =~ ^[1-9][0-9]{0,4}$ ]]; then
    echo "$0: TASKS: expected a whole number in [1, 99999], got '$tasks'" >&2
    exit 2
  fi
  if [ ! -f "$input" ]; then
    echo "$0: $name: no such file: $input" >&2
    exit 2
  fi
  asperity=$(realpath "${ASPERITY:-$here/../../build/asperity}")
  input=$(realpath "$input")
  # -s: resolving links would hand the jobs a link's target, a folder the user never named.
  out=$(realpath -m -s "$out")
  if [ -L "$out" ]; then
    echo "$0: OUT: refusing to write there: $out is a symbolic link; choose a new or empty folder" >&2
    exit 2
  fi
}

# submit_array_then TASK_SCRIPT FINAL_NAME FINAL_SCRIPT [FINAL_ARGS...]: the array (requeued when
# preempted) runs TASK_SCRIPT ASPERITY INPUT OUT; prints "array ID" and "FINAL_NAME ID".
submit_array_then() {
  local task_script=$1 final_name=$2 final_script=$3
  shift 3
  local array final
  array=$(sbatch --parsable --requeue --array="0-$((tasks - 1))" "${sbatch_options[@]}" "$task_script" "$asperity" "$input" "$out")
  array=${array%%;*}
  final=$(sbatch --parsable --dependency="afterok:$array" "${sbatch_options[@]}" "$final_script" "$@")
  final=${final%%;*}
  echo "array $array"
  echo "$final_name $final"
}
