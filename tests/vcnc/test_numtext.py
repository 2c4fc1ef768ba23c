"""The compiled %g / %d text of vcnc.core.numtext against Python's own % formatting, number by number."""

import numpy as np
import pytest

from vcnc.core.numtext import column_codes, format_chunks


def _python_text(data, fmt):
    return "".join(",".join(f % v for f, v in zip(fmt, row)) + "\n" for row in data.tolist())


def _compiled_text(data, fmt, rows=1000):
    return "".join(format_chunks(lambda a, b: data[a:b], len(data), column_codes(fmt), fmt, ",", rows))


def _edge_values(rng, n):
    """Magnitudes over the whole double range, short decimals, integers beyond 12 digits, random bit
    patterns (subnormals, NaNs of every payload), and exact rounding ties."""
    return np.concatenate([
        rng.standard_normal(n) * 10.0 ** rng.integers(-300, 300, size=n),
        rng.standard_normal(n) * 10.0 ** rng.integers(-6, 14, size=n),
        np.round(rng.standard_normal(n) * 1e6) / 10.0 ** rng.integers(0, 9, size=n),
        np.arange(n) * 0.001,
        rng.integers(-10**14, 10**14, size=n).astype(float),
        rng.integers(0, 2**63, size=n, dtype=np.uint64).view(float),
        # a 16-bit DAC's steps of 10 V / 2**15 (exact ties of the 12th digit are common) at several scales
        rng.integers(-2**15, 2**15, size=n) * (10.0 / 2**15) * 10.0 ** rng.integers(-6, 8, size=n),
        rng.integers(-2**40, 2**40, size=n) * 2.0 ** -rng.integers(0, 60, size=n).astype(float),
        # ties of the last digit kept, exact in binary: 0.25, 2.5, 1234567890125 (12 digits + 5), ...
        [-0.0, 0.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, np.inf, -np.inf, np.nan,
         0.25, 0.35, 2.5, 3.5, -2.5, 1234567890125.0, 1234567890135.0, 999999999999.5, 9999999999995.0,
         99999999999.95, 0.0001, 1e-5, 9.99999999999999e-5, 1e11, 1e12, 1e15, 1e16, 123456789012345678.0],
    ])


@pytest.mark.parametrize("prec", [1, 2, 6, 9, 12, 15])
def test_g_is_pythons_text(prec):
    rng = np.random.default_rng(prec)
    values = _edge_values(rng, 3000)
    data = values[: len(values) // 3 * 3].reshape(-1, 3)
    fmt = [f"%.{prec}g"] * 3
    assert _compiled_text(data, fmt) == _python_text(data, fmt)
    tail = values[-30:, None]  # the edge cases one per row, in every position of a chunk
    assert _compiled_text(tail, fmt[:1], rows=7) == _python_text(tail, fmt[:1])


def test_d_is_pythons_text():
    # %d truncates toward zero (-0.5 -> 0, not -0); beyond 2**62 Python formats it
    rng = np.random.default_rng(1)
    v = np.concatenate([rng.standard_normal(5000) * 10.0 ** rng.integers(-3, 20, size=5000),
                        [-0.5, 0.5, -0.0, 9.0, 10.0, -10.0, 4.6e18, -4.7e18, 2.0**62, 2.0**63]])
    data = np.column_stack([v * 1e-3, v])
    fmt = ["%.9g", "%d"]
    assert _compiled_text(data, fmt) == _python_text(data, fmt)


def test_column_blocks_are_written_as_their_table():
    # write_rows of blocks of columns side by side: the text of the stacked table, for both writers
    import io

    from vcnc.core.io import write_rows

    rng = np.random.default_rng(4)
    blocks = [rng.standard_normal((45_001, 1)), rng.standard_normal((45_001, 3)) * 1e3]
    for fmt in (["%.12g"] * 4, ["%.12g", "%.4f", "%.4f", "%.4f"]):
        got = io.StringIO()
        write_rows(got, blocks, fmt)
        assert got.getvalue() == _python_text(np.hstack(blocks), fmt)
    with pytest.raises(ValueError):
        write_rows(io.StringIO(), [blocks[0], blocks[1][:-1]], ["%.12g"] * 4)


def test_other_formats_are_not_compiled():
    assert column_codes(["%.12g", "%d"]).tolist() == [12, 0]
    assert column_codes(["%.12g", "%.3f"]) is None
    assert column_codes(["%.16g"]) is None  # 10**16 digits are past the integers a double holds exactly
    assert column_codes(["%g"]) is None
