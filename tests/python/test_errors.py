"""C++ errors arrive as Python exceptions with the command line's messages: a recipe with a typo
names its file, line and column; the exception classes map the command line's exit codes."""

import re
import shutil

import pytest

import geotandem
from conftest import SOURCE, cli


def typo_recipe(scratch_root):
    text = (SOURCE / "workflows" / "quickstart.yaml").read_text()
    assert "sigma_t_along: 3" in text
    bad = scratch_root / "typo.yaml"
    bad.write_text(text.replace("sigma_t_along: 3", "sigma_t_alnog: 3", 1))
    line = next(n for n, l in enumerate(bad.read_text().splitlines(), 1) if "sigma_t_alnog" in l)
    return bad, line


def test_a_recipe_with_a_typo_raises_with_file_line_and_column(scratch_root):
    recipe, line = typo_recipe(scratch_root)
    with pytest.raises(geotandem.RecipeError) as caught:
        geotandem.run_workflow(recipe, {"output.directory": scratch_root / "typo-out"}, progress=False)
    e = caught.value
    assert isinstance(e, ValueError) and e.exit_code == 2
    assert e.file == str(recipe) and e.line == line and e.column is not None
    assert f"{recipe}:{line}:{e.column}" in str(e)
    assert "sigma_t_alnog" in str(e)
    # The command line's message, word for word.
    run = cli("run-workflow", recipe, "--set", f"output.directory={scratch_root / 'typo-out'}", check=False)
    assert run.returncode == 2
    assert f"geotandem: error: {e}" in run.stderr
    assert not (scratch_root / "typo-out" / "store").exists()


def test_a_bad_override_and_a_missing_recipe(scratch_root):
    with pytest.raises(geotandem.InvalidArgumentError, match="steps.extract.iso"):
        geotandem.run_workflow(SOURCE / "workflows" / "quickstart.yaml",
                               {"steps.extract.iso": "high", "output.directory": scratch_root / "o"}, progress=False)
    with pytest.raises(geotandem.IoError) as e:
        geotandem.run_workflow(scratch_root / "missing.yaml", progress=False)
    assert isinstance(e.value, OSError) and e.value.exit_code == 3


def test_dry_run_and_version():
    outcome = geotandem.run_workflow(SOURCE / "workflows" / "quickstart.yaml", dry_run=True, progress=False)
    assert outcome["store"] is None
    assert re.fullmatch(r"\d+\.\d+\.\d+", geotandem.__version__)
    assert cli("--version").stdout.split()[-1] == geotandem.__version__
