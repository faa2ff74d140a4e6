#!/usr/bin/env bash
# A parameter study is a shell loop: solve the paper's brick for several friction parameters and
# mesh sizes with --set, then collect one line per run from each report.json into a CSV.
#   bash examples/parameter-study.sh [FRICON] [OUTDIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
fricon="${1:-$here/../build/apps/fricon/fricon}"
out="${2:-results/parameter-study}"
mkdir -p "$out"

for n in 4 6; do
  for param in 2e4 6e4 3e5; do
    "$fricon" solve "$here/paper-brick.toml" --quiet --out "$out/n$n-param$param" \
      --set "mesh.cells=[$((3 * n)),$n,$n]" --set "contact.friction.param=$param"
  done
done

# One CSV line per run, from the reports (Debian's Python: /usr/bin/python3).
/usr/bin/python3 - "$out" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
rows = ["run,n_primal,n_dual,outer_iterations,n_mult,wn_pos_inf,max_wt,max_lambda_t"]
for report in sorted(out.glob("*/report.json")):
    r = json.loads(report.read_text())
    rows.append(",".join(str(v) for v in [report.parent.name, r["n_primal"], r["n_dual"],
                r["outer_iterations"], r["n_mult"], r["wn_pos_inf"], r["max_wt"], r["max_lambda_t"]]))
(out / "summary.csv").write_text("\n".join(rows) + "\n")
print("\n".join(rows))
PY
