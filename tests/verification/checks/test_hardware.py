"""The Sec 4.3 / App. A hardware rows of `iik verify` (quick mode, simulated arm)."""

import re

from verification import Context, Verdict, run_checks
from verification.checks import hardware as hw


def test_hardware_section_quick(tmp_path):
    results = run_checks(Context(out_dir=tmp_path, quick=True), select=["Hardware"])
    assert results, "no hardware checks registered"
    assert all(r.check.section == hw.SECTION for r in results)
    failed = [(r.check.name, r.error) for r in results if r.error]
    assert not failed, failed
    rows = [row for r in results for row in r.rows]
    refs = " ".join(row.reference for row in rows)
    for ref in ("Table V", "Sec 4.3.1", "Sec 4.3.2", "App. A"):
        assert ref in refs, f"no row for {ref}"
    for row in rows:
        assert isinstance(row.verdict, Verdict)
        if row.verdict is not Verdict.NOT_CHECKABLE:
            assert re.search(r"\d", row.numbers), f"{row.reference}: no numbers in {row.numbers!r}"
    by_claim = {row.reference: row for row in rows}
    # every Table V function round-trips against the simulated modules
    table_v = next(row for row in rows if row.reference == "Sec 4.3, App. A, Table V")
    assert table_v.verdict is Verdict.HOLDS, table_v.numbers
    # the real arm's errors are explicitly not checkable
    assert by_claim["Sec 4.3.1, 4.3.2"].verdict is Verdict.NOT_CHECKABLE
    # the two printed Table V / App. A mistakes are recorded as errata
    errata = [e.equation for row in rows for e in row.errata]
    assert "Table V (PCube_setMaxCur)" in errata and "App. A (citation)" in errata


def test_early_update_measures_rests_and_errors(tmp_path):
    ctx = Context(out_dir=tmp_path, quick=True)
    wait = hw.execute_scenario(ctx, "j", early=1.0)
    thesis = hw.execute_scenario(ctx, "j")
    assert thesis is hw.execute_scenario(ctx, "j"), "runs are cached per context"
    assert wait.steps == thesis.steps > 2 and wait.changes == 6 * (wait.steps - 2)
    # waiting for each step to finish leaves joints at rest between steps; the 95 % update does not
    assert wait.rests > thesis.rests
    # every step-point is measured and the path starts and ends on the plan
    assert len(thesis.ee_error) == thesis.steps
    assert thesis.ee_error[0] < 1e-4 and thesis.ee_error[-1] < 1e-4
    assert thesis.min_clearance > 0.0


def test_fast_forward_clock_skips_waits_only():
    import time

    clock, sleep = hw.fast_forward_clock(20.0)
    c0, r0 = clock(), time.monotonic()
    sleep(0.4)
    advanced, real = clock() - c0, time.monotonic() - r0
    assert advanced >= 0.4 and real < 0.2  # the clock advanced by the whole wait, real time by ~1/20
    c1, r1 = clock(), time.monotonic()
    sum(range(200_000))  # computation runs at real speed
    assert abs((clock() - c1) - (time.monotonic() - r1)) < 5e-3
