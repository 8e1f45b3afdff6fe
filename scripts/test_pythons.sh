#!/usr/bin/env bash
# The supported Pythons besides the one the README's test command uses (3.11 here): for each,
# a fresh virtualenv with urdf-lint and its test tools, then a fast subset of the suite (the
# demo, expand, the sandbox, the worker channel, the CLI conventions, the pytest plugin, a
# corpus slice). Then the install path users take: `python -m build` makes an sdist and a
# wheel, the wheel is installed (not editable) into a fresh virtualenv, and the demo runs from
# it outside the checkout, on 3.12 and on the system's own Python.
# `system` is the distribution's Python, /usr/bin/python3 (Debian 12: 3.11.2, what ROS users
# on apt installs run; issue 31): in the default list when it exists (its venv module needs
# apt's python3-venv: .ci/run installs it).
# A Python that is missing is a failure, not a skip. PYTHONS overrides the list.
set -euo pipefail
cd "$(dirname "$0")/.."
SYSTEM_PYTHON=/usr/bin/python3
default="3.10 3.12 3.13"
[ -x "$SYSTEM_PYTHON" ] && default="$default system"
PYTHONS=${PYTHONS:-$default}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

find_python() {   # python3.X on PATH (a real one, not a pyenv shim without it), else pyenv's
  local v=$1 p
  if [ "$v" = system ]; then
    [ -x "$SYSTEM_PYTHON" ] && "$SYSTEM_PYTHON" -c 'import ensurepip, venv' >/dev/null 2>&1 &&
      echo "$SYSTEM_PYTHON" && return 0
    return 1
  fi
  if p=$(command -v "python$v") && "$p" -c 'import sys' >/dev/null 2>&1; then
    echo "$p"; return 0
  fi
  for p in "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$v".*/bin/"python$v"; do
    if [ -x "$p" ]; then echo "$p"; return 0; fi
  done
  return 1
}

SUBSET=(tests/test_architecture.py tests/test_sandbox.py tests/test_cli_conventions.py
        tests/test_startup.py tests/test_pytest_plugin.py tests/test_expand_corpus.py
        tests/test_wire.py
        "tests/test_accuracy.py::test_broken_demo_shows_every_class"
        # YAML/arg tracing, fresh-repository patterns, branch exploration, the SRDF checks
        # and the preview server: what the last issues added, on every Python
        tests/test_value_tracing.py tests/test_fresh_repository_patterns.py
        tests/test_explore.py tests/test_srdf.py tests/test_preview.py
        tests/test_mesh_store.py tests/test_review_diff.py
        # where fixes may write (urdf_lint/fix/scope.py: check --fix, generated URDFs,
        # --add-suppressions, the editor's code actions) and a warm run's imports
        "tests/test_fixes.py::test_files_outside_the_linted_paths_are_not_edited"
        "tests/test_fixes.py::test_add_suppressions"
        "tests/test_real_world_patterns.py::test_unsafe_fixes_never_rewrite_a_generated_urdf"
        "tests/test_server_confinement.py::test_code_actions_offer_no_edit_of_a_file_check_fix_refuses"
        "tests/test_lazy_imports.py::test_warm_run_imports_nothing_heavy"
        # the hook's changed files matched to the models as os.path.realpath matches them
        "tests/test_repo_workflows.py::test_affected_resolves_each_file_as_realpath_does"
        "tests/test_cache.py::test_the_wheels_record_is_read_as_importlib_metadata_reads_it"
        "tests/test_mesh_speed.py::test_a_variant_goes_to_the_worker_that_linted_its_model"
        "tests/test_mesh_speed.py::test_a_hull_is_computed_on_one_cpu_and_the_others_are_given_back"
        "tests/test_mesh_speed.py::test_a_model_of_many_macro_calls_is_scheduled_first"
        # the seconds a worker measured cross the plain-data channel into the signed record,
        # and plan the next run (scheduling by measured cost); numpy preloaded for two workers
        "tests/test_cache.py::test_a_relinted_model_is_planned_at_the_seconds_it_took_when_last_linted"
        "tests/test_cache.py::test_a_recorded_cost_that_is_no_number_of_seconds_is_not_believed"
        "tests/test_mesh_speed.py::test_the_seconds_models_took_before_plan_the_workers_in_place_of_the_estimates"
        "tests/test_mesh_speed.py::test_the_parent_preloads_numpy_for_the_geometry_rules_even_with_no_mesh_to_read"
        # macro bodies cloned from minidom's node fields, checked against minidom's clone,
        # and the mass integrals: minidom and numpy differ between the Pythons
        tests/test_expansion_clone.py
        "tests/test_mesh_speed.py::test_mass_properties_equal_trimesh_and_vertex_grouping_bitwise"
        "tests/test_mesh_speed.py::test_a_small_part_far_from_its_origin_keeps_its_precision"
        "tests/test_mesh_speed.py::test_mass_properties_are_trimeshs_across_blocks"
        "tests/test_mesh_speed.py::test_unique_first_is_np_uniques_even_when_keys_share_their_high_bits"
        # textured COLLADA read with lxml where pycollada loads the textures (pycollada's
        # and lxml's versions follow the Python)
        "tests/test_mesh_speed.py::test_textured_collada_is_read_by_lxml_only_when_pycollada_loads_its_textures"
        "tests/test_mesh_speed.py::test_collada_effect_trimesh_cannot_load_is_left_to_it")

for v in $PYTHONS; do
  py=$(find_python "$v") || { echo "test_pythons: Python $v is not installed (system: or it" \
    "has no venv module)" >&2; exit 1; }
  echo "== Python $v ($py, $("$py" -c 'import platform; print(platform.python_version())')):" \
    "fresh virtualenv, the fast subset"
  "$py" -m venv "$work/venv$v"
  if ! "$work/venv$v/bin/python" -m pip install -q -e '.[test]' >"$work/pip$v.log" 2>&1; then
    cat "$work/pip$v.log" >&2; echo "test_pythons: install failed on Python $v" >&2; exit 1
  fi
  "$work/venv$v/bin/python" -m pytest -q -p no:cacheprovider "${SUBSET[@]}"
done

echo "== the wheel: built, installed into a fresh virtualenv, the demo run from it"
rm -rf "$work/dist"
.venv/bin/python -m build -q --outdir "$work/dist" . >"$work/build.log" 2>&1 || {
  cat "$work/build.log" >&2; exit 1; }
ls "$work/dist"
wheel=$(ls "$work"/dist/urdf_lint-*.whl)
ls "$work"/dist/urdf_lint-*.tar.gz >/dev/null
want=$(grep -o 'Found [0-9]* problem(s) ([^)]*) in [0-9]* model(s)\.' README.md | head -n 1)

wheel_demo() {   # a copy of the demo linted (no cache: the workers run) by urdf-lint installed
  local py=$1 name=$2 rc   # from the wheel on Python $1 ($2: a name)
  echo "== the wheel on $name ($py)"
  "$py" -m venv "$work/wheel-$name"
  "$work/wheel-$name/bin/python" -m pip install -q "$wheel"
  mkdir -p "$work/$name" && cp -r descriptions "$work/$name/demo"
  set +e
  ( cd "$work/$name" && "$work/wheel-$name/bin/urdf-lint" check demo --no-cache ) \
    >"$work/demo-$name.log" 2>&1
  rc=$?
  set -e
  tail -n 1 "$work/demo-$name.log"
  if [ "$rc" != 1 ] || [ "$(tail -n 1 "$work/demo-$name.log")" != "$want" ]; then
    cat "$work/demo-$name.log" >&2
    echo "test_pythons: the demo from the installed wheel on $name exited $rc and did not" \
      "end with: $want" >&2
    exit 1
  fi
}

py=$(find_python 3.12) || py=python3
wheel_demo "$py" 3.12
( cd "$work/3.12" && "$work/wheel-3.12/bin/urdf-lint" check demo/r2d2_description && \
  "$work/wheel-3.12/bin/urdf-lint" rules >/dev/null && "$work/wheel-3.12/bin/urdf-lint" doctor )
case " $PYTHONS " in
  *" system "*) wheel_demo "$(find_python system)" system ;;
esac
echo "test_pythons: $PYTHONS and the wheel: ok"
