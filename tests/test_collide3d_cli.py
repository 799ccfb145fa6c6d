"""``impact collide3d`` through the real entry point: the smooth limit equals collide2d, the
gross-slip closed form, the Mindlin force history, and one-line errors."""

from __future__ import annotations

import csv
import gzip
import io
import json

import numpy as np
import pytest

ALUMINA_ON_PLANE = [
    "collide3d",
    "--d1", "5mm", "--E1", "380GPa", "--nu1", "0.23", "--rho1", "4000",
    "--d2", "inf", "--m2", "inf", "--E2", "inf",
    "--p1", "0,0,0", "--p2=0,0,-1", "--mu", "0.092",
]  # fmt: skip


def rows(text: str) -> dict[str, float]:
    (row,) = list(csv.DictReader(io.StringIO(text)))
    return {k: float(v) for k, v in row.items()}


def test_mu_zero_equals_collide2d(impact):
    # The paper's example of sec. 4.5.3 in the plane z = 0, elastic (e = 1), with spin.
    v1, v2 = "2.598076211353316,-1.5", "1.2855752193730785,1.532088886237956"
    two = impact("collide2d", "--m1", "0.05", "--m2", "0.15", "--v1", v1, "--v2", v2,
                 "--p1=-1,2", "--p2=2,-2", "-f", "csv")  # fmt: skip
    three = impact(
        "collide3d", "--d1", "40mm", "--d2", "60mm", "--E", "210GPa", "--nu", "0.3",
        "--m1", "0.05", "--m2", "0.15", "--v1", v1 + ",0", "--v2", v2 + ",0",
        "--w1", "0,0,30", "--p1=-1,2,0", "--p2=2,-2,0", "--mu", "0", "-f", "csv",
    )  # fmt: skip
    assert two.returncode == 0 and three.returncode == 0, three.stderr
    a, b = rows(two.stdout), rows(three.stdout)
    for key in ("v1_final_x", "v1_final_y", "v2_final_x", "v2_final_y"):
        assert b[key] == a[key]
    assert b["v1_final_z"] == 0.0 and b["w1_final_z"] == 30.0
    assert b["restitution"] == 1.0


def test_gross_slip_closed_form(impact):
    # 3.9 m/s at 60 deg: v_t' = v_t - 2 mu v_n, w' = 5 mu v_n / R (e = 1).
    vt, vn = 3.9 * float(np.sin(np.radians(60))), 3.9 * float(np.cos(np.radians(60)))
    for model in ("rigid", "mindlin"):
        r = impact(*ALUMINA_ON_PLANE, f"--v1={vt!r},0,{-vn!r}", "--tangential", model,
                   "--points", "801", "-f", "json")  # fmt: skip
        assert r.returncode == 0, r.stderr
        s = json.loads(r.stdout)["summary"]
        assert s["v1_final_x"] == pytest.approx(vt - 2 * 0.092 * vn, rel=1e-12)
        assert s["w1_final_y"] == pytest.approx(5 * 0.092 * vn / 2.5e-3, rel=1e-11)
        assert s["stuck"] == 0.0
        assert s["energy_dissipated2_friction"] == 0.0


def test_mindlin_json_has_the_force_history(impact):
    r = impact(*ALUMINA_ON_PLANE, "--v1=1.95,0,-3.3775", "--tangential", "mindlin",
               "--points", "501", "-f", "json")  # fmt: skip
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    force = doc["tangential_force"]
    assert len(force["t"]) == len(force["force"]) == 501
    assert doc["summary"]["tangential_restitution"] > 0.0  # the slip reverses at 30 deg
    assert doc["summary"]["rebound_angle"] < 0.0


def test_table_output(impact):
    r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "-f", "table")
    assert r.returncode == 0, r.stderr
    assert "tangential restitution" in r.stdout and "Energy dissipated" in r.stdout


@pytest.mark.parametrize(
    "args, message",
    [
        (["--v1=1,0,-3", "--mu", "-1"], "--mu"),
        (["--v1=1,-3"], "three components"),
        (["--v1=1,0,3"], "not approaching"),
        (["--v1=1,0,-3", "--w1", "a,b,c"], "--w1"),
        (["--v1=1,0,-3", "--e", "0", "--tangential", "mindlin"], "--e 0"),
        (["--v1=1,0,-3", "--w2", "0,1,0"], "flat target cannot spin"),
    ],
)
def test_bad_input_one_line(impact, args, message):
    r = impact(*ALUMINA_ON_PLANE, *args)
    assert r.returncode == 2
    assert message in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert "Traceback" not in r.stderr


@pytest.mark.slow
def test_plots(impact, tmp_path):
    pytest.importorskip("matplotlib")
    diagram, force = tmp_path / "c3d.png", tmp_path / "force.svg"
    r = impact(*ALUMINA_ON_PLANE, "--v1=1.95,0,-3.3775", "--tangential", "mindlin",
               "--points", "401", "-f", "csv", "--plot", str(diagram),
               "--plot-force", str(force))  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert diagram.stat().st_size > 0 and force.stat().st_size > 0
    bad = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--plot-force", str(tmp_path / "x.png"))
    assert bad.returncode == 2 and "--tangential mindlin" in bad.stderr
    assert not (tmp_path / "x.png").exists()


def test_speed_and_angles_equal_components(impact):
    # 3.9 m/s at 30 deg from n = -z toward +x (phi = 0), and at phi = 90 deg toward +y.
    a = impact(*ALUMINA_ON_PLANE, "--v1", "3.9m/s@30deg", "-f", "json")
    s, c = 3.9 * float(np.sin(np.radians(30.0))), 3.9 * float(np.cos(np.radians(30.0)))
    b = impact(*ALUMINA_ON_PLANE, f"--v1={s!r},0,{-c!r}", "-f", "json")
    d = impact(*ALUMINA_ON_PLANE, "--v1", "3.9@30@90", "-f", "json")
    assert a.returncode == b.returncode == d.returncode == 0, a.stderr + d.stderr
    va, vb = json.loads(a.stdout)["inputs"]["v1"], json.loads(b.stdout)["inputs"]["v1"]
    assert va == pytest.approx(vb, rel=1e-15, abs=1e-15)
    vd = json.loads(d.stdout)["inputs"]["v1"]
    assert vd == pytest.approx([0.0, s, -c], rel=1e-15, abs=1e-15)


def test_angular_velocity_units(impact):
    # 600 rpm = 20 pi rad/s about the normal: the rigid model leaves that spin alone.
    r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--w1", "0,0,600rpm", "-f", "json")
    q = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--w1", "100rad/s,0,0", "-f", "json")
    assert r.returncode == 0 and q.returncode == 0, r.stderr + q.stderr
    doc = json.loads(r.stdout)
    assert doc["inputs"]["w1"][2] == pytest.approx(20 * np.pi, rel=1e-15)
    assert doc["summary"]["w1_final_z"] == doc["inputs"]["w1"][2]
    assert json.loads(q.stdout)["inputs"]["w1"] == [100.0, 0.0, 0.0]


def test_law_and_damping_give_the_head_on_restitution(impact):
    """e of collide3d is the head-on impact's at the normal approach velocity u_n."""
    from impactcli.damping import TsujiDamping, solve_damped_impact
    from impactcli.impact import Sphere, law_impact

    ball = Sphere(5e-3, 380e9, 0.23, 4000.0)
    plane = Sphere(np.inf, np.inf, 0.0, mass=np.inf, yield_strength=2e9)
    thornton = law_impact(ball, plane, 3.0, 0.0, "thornton").summary["restitution"]
    r = impact(*ALUMINA_ON_PLANE, "--sy2", "2GPa", "--v1=1,0,-3", "--law", "thornton",
               "-f", "json")  # fmt: skip
    walton = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--law", "walton-braun", "--k-load",
                    "1MN/m", "--k-unload", "4e6", "-f", "json")  # fmt: skip
    assert walton.returncode == 0, walton.stderr
    assert json.loads(walton.stdout)["summary"]["restitution"] == pytest.approx(0.5, rel=1e-12)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["summary"]["restitution"] == pytest.approx(thornton, rel=1e-12)
    assert thornton < 1.0
    m = ball.total_mass
    k = 4.0 / 3.0 * (380e9 / (1 - 0.23**2)) * np.sqrt(2.5e-3)
    tsuji = float(solve_damped_impact(TsujiDamping(k, m, 0.2), 3.0, m).restitution)
    for model in ("rigid", "mindlin"):
        d = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--damping", "tsuji", "--alpha", "0.2",
                   "--tangential", model, "--points", "801", "-f", "json")  # fmt: skip
        assert d.returncode == 0, d.stderr
        summary = json.loads(d.stdout)["summary"]
        assert summary["restitution"] == pytest.approx(tsuji, rel=1e-12)
        assert summary["normal_restitution"] == pytest.approx(tsuji, rel=1e-12)


def test_hunt_crossley_alpha_with_unit_as_impact_elastic(impact):
    """--damping and --alpha (with its unit) are the shared options of impact elastic:
    collide3d's normal restitution at u_n = 3 m/s is the head-on impact's at 3 m/s."""
    hunt = ["--damping", "hunt-crossley", "--alpha", "0.5s/m"]
    head_on = impact("elastic", *ALUMINA_ON_PLANE[1:15], "--v1", "3", "--v2", "0", *hunt,
                     "-f", "json")  # fmt: skip
    assert head_on.returncode == 0, head_on.stderr
    e = json.loads(head_on.stdout)["summary"]["restitution"]
    assert 0.0 < e < 1.0
    for model in ("rigid", "mindlin"):
        r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", *hunt, "--tangential", model,
                   "--points", "801", "-f", "json")  # fmt: skip
        assert r.returncode == 0, r.stderr
        doc = json.loads(r.stdout)
        assert doc["summary"]["normal_restitution"] == pytest.approx(e, rel=1e-12)
        assert doc["inputs"]["normal_model"] == "hunt-crossley damping (alpha = 0.5)"
    # the same alpha written in SI: the same collision
    si = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", "--damping", "hunt-crossley", "--alpha",
                "0.5", "-f", "json")  # fmt: skip
    assert json.loads(si.stdout)["summary"]["normal_restitution"] == pytest.approx(e, rel=1e-12)


def test_separation_reaches_the_damped_normal_law(impact, tmp_path):
    """--separation force: the contact ends when the total force returns to 0, as in impact
    elastic (a larger e than overlap for tsuji), for one collision and for --rows."""
    pytest.importorskip("pyarrow")
    tsuji = ["--damping", "tsuji", "--alpha", "0.5"]
    found = {}
    for rule in ("overlap", "force"):
        head_on = impact("elastic", *ALUMINA_ON_PLANE[1:15], "--v1", "3", "--v2", "0", *tsuji,
                         "--separation", rule, "-f", "json")  # fmt: skip
        assert head_on.returncode == 0, head_on.stderr
        e = found[rule] = json.loads(head_on.stdout)["summary"]["restitution"]
        for model in ("rigid", "mindlin"):
            r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", *tsuji, "--separation", rule,
                       "--tangential", model, "--points", "801", "-f", "json")  # fmt: skip
            assert r.returncode == 0, r.stderr
            assert json.loads(r.stdout)["summary"]["normal_restitution"] == pytest.approx(
                e, rel=1e-12
            )
        table, out = tmp_path / f"{rule}.csv", tmp_path / f"{rule}-out.csv"
        table.write_text(ROWS_HEADER + "\n0,0,0,0,0,-1,1,0,-3,0,0,0,5mm,inf,inf,380GPa,0.23,"
                         "4000,inf\n")  # fmt: skip
        r = impact("collide3d", "--rows", str(table), "-o", str(out), *tsuji,
                   "--separation", rule)  # fmt: skip
        assert r.returncode == 0, r.stderr
        (row,) = list(csv.DictReader(out.open()))
        assert float(row["normal_restitution"]) == pytest.approx(e, rel=1e-12)
    assert found["force"] > found["overlap"]


@pytest.mark.parametrize(
    "args, message",
    [
        (["--alpha", "0.2"], "--alpha needs --damping"),
        (["--separation", "force"], "--separation needs --damping"),
        (["--damping", "tsuji", "--alpha", "0.2", "--e", "0.5"], "one normal law"),
        (["--damping", "tsuji", "--alpha", "0.5s/m"], "--alpha"),  # tsuji's alpha is [-]
        (["--damping", "tsuji", "--alpha", "0.2", "--separation", "glue"], "--separation"),
    ],
)
def test_damping_option_errors_one_line(impact, args, message):
    r = impact(*ALUMINA_ON_PLANE, "--v1=1,0,-3", *args)
    assert r.returncode == 2, r.stdout
    assert message in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize(
    "args, message",
    [
        (["--nu2", "0.7"], "sphere 2: Poisson's ratio"),  # checked, though unused
        (["--law", "nope"], "unknown law"),
        (["--law", "hertz", "--model", "elastic"], "one normal law"),
        (["--damping", "tsuji"], "--alpha"),
        (["--damping", "tsuji", "--alpha", "-1"], "--alpha"),
        (["--py", "1GPa"], "--py is a parameter of law thornton"),
        (["--law", "thornton", "--k-load", "1e6"], "--k-load is a parameter of law walton-braun"),
        (["--v1", "3.9m/s@30deg@1@2"], "SPEED@THETA"),
        (["--v1", "-3m/s@30deg"], "speed must be >= 0"),
        (["--w1", "0,0,3Hz"], "angular velocity"),
        (["--law", "du-wang"], "yield strength"),
    ],
)
def test_more_bad_input_one_line(impact, args, message):
    r = impact(*ALUMINA_ON_PLANE, *(args if "--v1" in args else ["--v1=1,0,-3", *args]))
    assert r.returncode == 2, r.stdout
    assert message in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


ROWS_HEADER = "p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,w1_x,w1_y,w1_z,d1,d2,m2,E1,nu1,rho1,E2"


def _rows_table(angles) -> str:
    lines = [ROWS_HEADER]
    for deg in angles:
        vt, vn = 3.9 * float(np.sin(np.radians(deg))), 3.9 * float(np.cos(np.radians(deg)))
        lines.append(f"0,0,0,0,0,-1,{vt!r},0,{-vn!r},0,0,0,5mm,inf,inf,380GPa,0.23,4000,inf")
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("model", ["rigid", "mindlin", "mindlin-displacement",
                                   "mindlin-deresiewicz"])  # fmt: skip
def test_rows_equal_single_collisions(impact, tmp_path, model):
    """Each row of --rows gives the numbers of the single command; a bad row gets its
    reason in the error column, the others are computed."""
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_text(_rows_table([10.0, 50.0]) + "0,0,0,0,0,-1,1,0,3,0,0,0,5mm,inf,inf,380GPa,"
                     "0.23,4000,inf\n0,0,0,0,0,-1,1,0,-3,0,0,0,5mm,inf,inf,380GPa,0.23,4000,\n")
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(table), "-o", str(out), "--mu", "0.092",
               "--tangential", model, "--points", "801")  # fmt: skip
    assert r.returncode == 0, r.stderr
    got = list(csv.DictReader(out.open()))
    assert len(got) == 4
    assert "not approaching" in got[2]["error"] and got[2]["v1_final_x"] == ""
    assert "sphere 2: Young's modulus unknown" in got[3]["error"]
    assert "row 3:" in r.stderr and "2 of 4 rows invalid" in r.stderr
    for row, deg in zip(got[:2], (10.0, 50.0)):
        assert row["error"] == ""
        vt, vn = 3.9 * float(np.sin(np.radians(deg))), 3.9 * float(np.cos(np.radians(deg)))
        one = impact(*ALUMINA_ON_PLANE, f"--v1={vt!r},0,{-vn!r}", "--tangential", model,
                     "--points", "801", "-f", "csv")  # fmt: skip
        single = rows(one.stdout)
        for key in ("v1_final_x", "w1_final_y", "tangential_restitution", "rebound_angle"):
            assert float(row[key]) == pytest.approx(single[key], rel=1e-10, abs=1e-12)  # 12 digits


def test_rows_name_their_own_tangential_model(impact, tmp_path):
    """A ``tangential`` column gives each row its model by the names of --tangential (an
    empty cell: the command's); each row has the numbers of the command run with its model,
    and an unknown name is that row's error, naming the accepted ones."""
    pytest.importorskip("pyarrow")
    models = ["mindlin-displacement", "rigid", "", "mindlin-deresiewicz", "mindlin-rescal"]
    lines = _rows_table([10.0] * len(models)).splitlines()
    table = tmp_path / "in.csv"
    table.write_text("\n".join([lines[0] + ",tangential"]
                               + [f"{line},{m}" for line, m in zip(lines[1:], models)]) + "\n")
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(table), "-o", str(out), "--mu", "0.092",
               "--tangential", "mindlin-force", "--points", "801")  # fmt: skip
    assert r.returncode == 0, r.stderr
    got = list(csv.DictReader(out.open()))
    assert [row["tangential"] for row in got] == models
    assert "unknown tangential model 'mindlin-rescal'; accepted: rigid, mindlin" in got[4]["error"]
    vt, vn = 3.9 * float(np.sin(np.radians(10.0))), 3.9 * float(np.cos(np.radians(10.0)))
    spins = set()
    for row, model in zip(got[:4], ["mindlin-displacement", "rigid", "mindlin-force",
                                    "mindlin-deresiewicz"]):  # fmt: skip
        assert row["error"] == ""
        one = impact(*ALUMINA_ON_PLANE, f"--v1={vt!r},0,{-vn!r}", "--tangential", model,
                     "--points", "801", "-f", "csv")  # fmt: skip
        single = rows(one.stdout)
        for key in ("v1_final_x", "w1_final_y", "tangential_restitution"):
            assert float(row[key]) == pytest.approx(single[key], rel=1e-10, abs=1e-12)
        spins.add(round(float(row["w1_final_y"]), 3))
    assert len(spins) == 4  # four models, four answers


def test_rows_refuses_single_options_and_bad_headers(impact, tmp_path):
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_text(_rows_table([10.0]))
    r = impact("collide3d", "--rows", str(table), "--v1=1,0,-3")
    assert r.returncode == 2 and "--v1" in r.stderr
    bad = tmp_path / "bad.csv"
    bad.write_text("p1_x,p1_y\n0,0\n")
    r = impact("collide3d", "--rows", str(bad), "-o", str(tmp_path / "o.csv"))
    assert r.returncode == 2 and "missing input column(s)" in r.stderr
    assert not (tmp_path / "o.csv").exists()


# -- --rows through the table layer of impact batch -------------------------------------------


def test_rows_short_line_is_one_error_row(impact, tmp_path):
    """A malformed CSV line is an error row, as in impact batch; the good rows are kept."""
    pytest.importorskip("pyarrow")
    good = _rows_table([10.0, 50.0]).splitlines()
    table = tmp_path / "in.csv"
    table.write_text("\n".join([good[0], good[1], "0,0,0,0,0,-1,1,0", good[2]]) + "\n")
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(table), "-o", str(out), "--mu", "0.092")
    assert r.returncode == 0, r.stderr
    got = list(csv.DictReader(out.open()))
    assert len(got) == 3
    assert got[1]["error"].startswith("malformed line:") and got[1]["v1_final_x"] == ""
    assert got[0]["error"] == got[2]["error"] == ""
    assert got[0]["v1_final_x"] != "" and got[2]["v1_final_x"] != ""
    assert "row 2: malformed line" in r.stderr and "1 of 3 rows invalid" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.parametrize(
    "content, message",
    [
        (gzip.compress(_rows_table([10.0]).encode()), "gzip-compressed input"),
        (_rows_table([10.0]).encode("utf-16"), "UTF-16/UTF-32 text"),
        (b"PK\x03\x04\x00\x00binary", "binary input"),
    ],
    ids=["gzip", "utf16", "binary"],
)
def test_rows_refuses_input_kinds_in_one_line(impact, tmp_path, content, message):
    """gzip, UTF-16 and binary input: the one-line refusal of impact batch, no file left."""
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_bytes(content)
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(table), "-o", str(out))
    assert r.returncode == 2
    assert message in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not out.exists() and list(tmp_path.iterdir()) == [table]


def test_rows_parquet_list_column(impact, tmp_path):
    """A list column cannot go to CSV: one line, no traceback, no file; Parquet carries it."""
    pa = pytest.importorskip("pyarrow")
    from pyarrow import csv as pa_csv
    from pyarrow import parquet as pq

    source = tmp_path / "in.csv"
    source.write_text(_rows_table([10.0, 50.0]))
    table = pa_csv.read_csv(source)
    table = table.append_column("tags", pa.array([[1, 2], [3]]))
    pq.write_table(table, tmp_path / "in.parquet")
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(tmp_path / "in.parquet"), "-o", str(out))
    assert r.returncode == 2 and "column tags holds list" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and not out.exists()
    r = impact("collide3d", "--rows", str(tmp_path / "in.parquet"), "-o",
               str(tmp_path / "out.parquet"), "--mu", "0.092")  # fmt: skip
    assert r.returncode == 0, r.stderr
    got = pq.read_table(tmp_path / "out.parquet")
    assert got.column("tags").to_pylist() == [[1, 2], [3]]
    assert got.column("error").to_pylist() == ["", ""]


@pytest.mark.parametrize("command", ["batch", "collide3d"])
def test_table_output_refuses_other_extensions(impact, tmp_path, command):
    """-o OUT.json of a table command: one line naming the accepted extensions, no file."""
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_text(_rows_table([10.0]))
    out = tmp_path / "out.json"
    args = ["batch", str(table)] if command == "batch" else ["collide3d", "--rows", str(table)]
    r = impact(*args, "-o", str(out))
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert ".csv, .parquet" in r.stderr and "Traceback" not in r.stderr
    assert not out.exists()


def test_rows_failure_after_a_written_chunk_leaves_nothing(impact, tmp_path):
    """A line over the limit after chunks already written to Parquet: one line, exit 2, no
    file and no message of the abandoned Parquet writer."""
    pytest.importorskip("pyarrow")
    table = _rows_table([10.0, 50.0] * 10_000)
    source = tmp_path / "in.csv"
    source.write_text(table + "x" * (2 << 20) + "\n" + table.split("\n", 1)[1])
    out = tmp_path / "out.parquet"
    r = impact("collide3d", "--rows", str(source), "-o", str(out))
    assert r.returncode == 2 and "longer than" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    assert not out.exists() and list(tmp_path.iterdir()) == [source]


TWO_SPHERES = ["collide3d", "--d1", "10mm", "--d2", "20mm", "--material", "steel",
               "--p1", "0,0,0", "--v1=1,0.5,2", "--v2", "0,0,0", "--w1", "0,30,0",
               "--mu", "0.3", "-f", "csv"]  # fmt: skip


def test_centres_not_at_contact_are_refused_with_friction(impact, tmp_path):
    """Two spheres with friction whose centres are not R1 + R2 apart: one line, exit 2,
    nothing written (the friction impulse would turn them about two different points and
    the angular momentum about the origin would change)."""
    out = tmp_path / "out.csv"
    r = impact(*TWO_SPHERES, "--p2", "1,1,1", "-o", str(out))
    assert r.returncode == 2 and not out.exists()
    assert r.stderr.count("\n") == 1
    assert "the centres are 1.732 m apart but the spheres touch at R1 + R2 = 0.015 m" in r.stderr
    assert "within 1e-06 of R1 + R2" in r.stderr


def test_two_spheres_at_contact_conserve_angular_momentum_about_the_origin(impact):
    """The same spheres at contact along (1, 1, 1): the angular momentum about the origin
    (and momentum) after equals before, for both tangential models."""
    p2 = ",".join([repr(float(0.015 / np.sqrt(3.0)))] * 3)
    for model in ("rigid", "mindlin"):
        r = impact(*TWO_SPHERES, "--p2", p2, "--tangential", model)
        assert r.returncode == 0, r.stderr
        got = rows(r.stdout)
        assert got["tangential_impulse"] > 0.0
        scale = max(abs(got[f"angular_momentum_origin_before_{a}"]) for a in "xyz")
        for axis in "xyz":
            before = got[f"angular_momentum_origin_before_{axis}"]
            after = got[f"angular_momentum_origin_after_{axis}"]
            assert after == pytest.approx(before, rel=0, abs=1e-10 * scale)


def test_rows_centres_not_at_contact_are_that_rows_error(impact, tmp_path):
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_text("p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,material\n"
                     "0,0,0,1,1,1,1,1,1,10mm,20mm,steel\n"
                     "0,0,0,0,0,15mm,1,0,2,10mm,20mm,steel\n")  # fmt: skip
    out = tmp_path / "out.csv"
    r = impact("collide3d", "--rows", str(table), "-o", str(out), "--mu", "0.3")
    assert r.returncode == 0, r.stderr
    got = list(csv.DictReader(out.open()))
    assert "the centres must be at contact" in got[0]["error"] and got[0]["v1_final_x"] == ""
    assert got[1]["error"] == "" and float(got[1]["tangential_impulse"]) > 0.0


def test_rows_carry_the_damped_friction_budget(impact, tmp_path):
    """A damped normal law with the overlap rule pulls at the end of the contact: the
    mindlin friction impulse of a --rows table, as of the single command, exceeds mu J_n
    (Coulomb's cap mu max(F, 0) integrates to more than mu J_n; tests/test_collision3d.py)."""
    pytest.importorskip("pyarrow")
    table = tmp_path / "in.csv"
    table.write_text("p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,m2,E2,E1,nu1,rho1\n"
                     "0,0,0,0,0,-1,11.342,0,-2,5mm,inf,inf,inf,380GPa,0.23,4000\n")  # fmt: skip
    damped = ["--mu", "0.2", "--tangential", "mindlin", "--damping", "tsuji", "--alpha", "0.25"]
    r = impact("collide3d", "--rows", str(table), *damped)
    assert r.returncode == 0, r.stderr
    (row,) = list(csv.DictReader(io.StringIO(r.stdout)))
    one = rows(impact(*ALUMINA_ON_PLANE[:-2], "--v1=11.342,0,-2", *damped, "-f", "csv").stdout)
    j_t, j_n = float(row["tangential_impulse"]), float(row["normal_impulse"])
    assert j_t == pytest.approx(one["tangential_impulse"], rel=1e-10)
    assert 1.009 < j_t / (0.2 * j_n) < 1.011


def test_rows_write_parquet_when_asked_as_batch_does(impact, tmp_path):
    """-f parquet was refused with --rows; it writes Parquet as impact batch does (to a
    file of any name), and a single collision says what it writes."""
    from pyarrow import parquet as pq

    source = tmp_path / "in.csv"
    source.write_text("p1_x,p1_y,p1_z,p2_x,p2_y,p2_z,v1_x,v1_y,v1_z,d1,d2,m2,E2,material1\n"
                      "0,0,0,0,0,-1,1,0,-2,5mm,inf,inf,inf,steel\n")  # fmt: skip
    out = tmp_path / "out"
    done = impact("collide3d", "--rows", str(source), "-f", "parquet", "-o", str(out))
    assert done.returncode == 0, done.stderr
    assert pq.read_table(out).num_rows == 1
    refused = impact("collide3d", "--rows", str(source), "-f", "json")
    assert refused.returncode == 2 and "-f csv or parquet" in refused.stderr
    single = impact("collide3d", "--d1", "5mm", "--material", "steel", "--d2", "inf", "--m2",
                    "inf", "--E2", "inf", "--p1", "0,0,0", "--p2=0,0,-1", "--v1", "0,0,-1",
                    "-f", "parquet")  # fmt: skip
    assert single.returncode == 2 and "-f parquet writes the table of --rows" in single.stderr


def test_each_tangential_model_by_name_and_the_geometry_in_the_result(impact):
    """--tangential names every model of the registry; JSON says the geometry used."""
    from impactcli.laws.tangential import tangential_names

    spins = {}
    for name in tangential_names():
        r = impact(*ALUMINA_ON_PLANE, "--v1", "3.9m/s@5deg", "--tangential", name, "-f", "json")
        assert r.returncode == 0, r.stderr
        document = json.loads(r.stdout)
        assert document["inputs"]["tangential_model"] == name
        assert document["inputs"]["geometry"] == "frozen"
        spins[name] = document["summary"]["w1_final_y"]
    assert len({round(v, 3) for v in spins.values()}) == len(spins)  # they differ at 5 deg


def test_e_with_a_spring_is_hertz_with_the_tsuji_damping_that_gives_it(impact):
    """--e 0.98 --tangential mindlin-displacement: e of the impact 0.98, the normal law said
    (Chung & Ooi's test 4 at 10 deg: 204.5 rad/s, their curve 213 digitised)."""
    r = impact(*ALUMINA_ON_PLANE, "--v1", "3.9m/s@10deg", "--e", "0.98", "--tangential",
               "mindlin-displacement", "-f", "json")  # fmt: skip
    assert r.returncode == 0, r.stderr
    document = json.loads(r.stdout)
    assert document["summary"]["normal_restitution"] == pytest.approx(0.98, abs=1e-9)
    assert document["inputs"]["normal_model"].startswith("tsuji damping for e = 0.98")
    assert document["summary"]["w1_final_y"] == pytest.approx(204.5, abs=0.1)


def test_n_sets_the_film_segments_of_the_normal_history(impact):
    """--n: the spin of a stick at 5 deg moves by 8e-5 between n = 25 and the default 100."""
    got = {}
    for n in ("25", "100"):
        r = impact(*ALUMINA_ON_PLANE, "--v1", "3.9m/s@5deg", "--tangential", "mindlin",
                   "--n", n, "-f", "json")  # fmt: skip
        got[n] = json.loads(r.stdout)["summary"]["w1_final_y"]
    default = impact(*ALUMINA_ON_PLANE, "--v1", "3.9m/s@5deg", "--tangential", "mindlin",
                     "-f", "json")  # fmt: skip
    assert json.loads(default.stdout)["summary"]["w1_final_y"] == got["100"]
    assert 5e-5 < abs(got["25"] / got["100"] - 1.0) < 2e-4


STEEL_PAIR = ["collide3d", "--d1", "20mm", "--d2", "20mm", "--material", "steel",
              "--p1", "0,0,0.02", "--p2", "0,0,0"]  # fmt: skip


def test_moving_geometry_turns_the_normal_of_two_spheres(impact):
    """Two equal steel spheres at 75 deg without friction: the frozen geometry keeps e_n = 1
    along the normal of first contact; the moving one turns the line of centres (0.64 deg)
    and e_n along the first normal is 0.958. The result says its geometry."""
    frozen = impact(*STEEL_PAIR, "--v1", "3.9m/s@75deg", "-f", "json")
    moving = impact(*STEEL_PAIR, "--v1", "3.9m/s@75deg", "--geometry", "moving", "-f", "json")
    assert moving.returncode == 0, moving.stderr
    f, m = (json.loads(r.stdout) for r in (frozen, moving))
    assert f["summary"]["normal_restitution"] == pytest.approx(1.0, abs=1e-12)
    assert m["summary"]["normal_restitution"] == pytest.approx(0.958, abs=5e-4)
    assert m["inputs"]["geometry"] == "moving"
    # momentum is conserved in either geometry
    for key in ("momentum_before_x", "momentum_before_z"):
        after = key.replace("before", "after")
        assert m["summary"][after] == pytest.approx(m["summary"][key], rel=1e-9, abs=1e-12)


def test_moving_geometry_tends_to_the_frozen_one_as_the_normal_stops_turning():
    """A sphere on a fixed sphere of 1 m radius (the normal turns by 1e-5 rad): the moving
    geometry's spin within 1e-4 of the frozen one's."""
    import math

    from impactcli.collision3d import (
        effective_shear_modulus,
        normal_restitution_and_history,
        oblique_collision_3d,
    )
    from impactcli.impact import Sphere
    from impactcli.moving import moving_collision_3d

    ball = Sphere.from_material(0.02, "steel")
    big = Sphere.from_material(2.0, "steel", mass=math.inf)
    v = 3.9 * np.array([np.sin(np.radians(5.0)), 0.0, -np.cos(np.radians(5.0))])
    p1 = np.array([0.0, 0.0, ball.radius + big.radius])
    moving = moving_collision_3d(ball, big, v, (0, 0, 0), p1, (0, 0, 0), mu=0.3,
                                 tangential="mindlin", points=2001)  # fmt: skip
    e, history = normal_restitution_and_history(ball, big, float(-v[2]), points=4001)
    g = effective_shear_modulus(ball.youngs_modulus, ball.poisson_ratio, big.youngs_modulus,
                                big.poisson_ratio)  # fmt: skip
    frozen = oblique_collision_3d(ball.total_mass, math.inf, v, (0, 0, 0), p1, (0, 0, 0),
                                  ball.diameter, big.diameter, restitution=e, mu=0.3,
                                  tangential="mindlin", history=history,
                                  shear_modulus=g)  # fmt: skip
    assert float(moving.w1_final[1]) == pytest.approx(float(frozen.w1_final[0, 1]), rel=1e-4)


@pytest.mark.parametrize(
    "args, message",
    [
        (["--d1", "5mm", "--material", "steel", "--d2", "inf", "--m2", "inf", "--p1", "0,0,0",
          "--p2=0,0,-1", "--v1", "1m/s@30deg", "--geometry", "moving"], "flat target"),
        ([*STEEL_PAIR[1:], "--v1", "1m/s@30deg", "--mu", "0.3", "--geometry", "moving"],
         "tangential spring"),
        ([*STEEL_PAIR[1:], "--v1", "1m/s@30deg", "--model", "elastoplastic", "--geometry",
          "moving"], "Hertz"),
        # as the frozen geometry says it: u_n and the normal
        ([*STEEL_PAIR[1:], "--v1=0,0,1", "--mu", "0.3", "--tangential", "mindlin",
          "--geometry", "moving"], "(v1 - v2).n = -1 m/s with n = (0, 0, -1)"),
    ],
)  # fmt: skip
def test_moving_geometry_refuses_what_it_does_not_cover(impact, args, message):
    r = impact("collide3d", *args)
    assert r.returncode == 2 and message in r.stderr, r.stderr
    assert r.stderr.startswith("impact: error:") and len(r.stderr.splitlines()) == 1
