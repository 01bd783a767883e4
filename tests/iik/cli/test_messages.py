"""iik.cli.messages: library errors carry their remedy in library terms; the CLI shows the options."""

import pytest

from iik.cli import build_parser, main
from iik.cli.messages import as_typed
from iik.errors import IIKError, InvalidInputError, Remedy


def _parser(command: str):
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    return sub.choices[command]


def test_a_remedy_names_the_library_argument_and_the_cli_its_option():
    err = InvalidInputError("margin", "too large", Remedy("choose a smaller {}", "margin"))
    assert str(err) == "margin: too large; choose a smaller margin" and err.problem == "margin: too large"
    assert as_typed(err, _parser("run")) == ("InvalidInputError: --margin-deg: too large; choose a smaller "
                                             "--margin-deg")


def test_a_switch_to_call_again_with_is_the_command_line():
    err = IIKError("module 3: halted")
    err.remedy = Remedy("reset it first: {}", "reset", True, rerun=True)
    assert str(err) == "module 3: halted; reset it first: reset=True"
    assert as_typed(err, _parser("run")) == "IIKError: module 3: halted; reset it first: iik run --reset"


def test_several_arguments_and_one_no_option_sets():
    remedy = Remedy("give exactly one of {}", ("scenario", "trajectory", "demo"))
    assert remedy.text() == "give exactly one of scenario, trajectory or demo"
    err = InvalidInputError("run", "no trajectory or more than one", remedy)
    assert as_typed(err, _parser("run")).endswith("give exactly one of SCENARIO, --trajectory or --demo")
    lone = InvalidInputError("x", "bad", Remedy("set {}", "not_an_option", 2))
    assert as_typed(lone, _parser("run")) == "InvalidInputError: x: bad; set not_an_option=2"


@pytest.mark.parametrize("argv, shown", [
    (["run", "--demo", "--trajectory", "t.csv"],
     "InvalidInputError: run: no trajectory or more than one; give exactly one of SCENARIO, --trajectory or "
     "--demo"),
    (["view", "--q", "0", "0", "0", "0", "0", "0", "--xyz", "0.4", "0", "0.2", "--zyz", "0", "3", "0"],
     "InvalidInputError: --q: a configuration and a pose were both given; give either --q or --xyz"),
    (["view", "--xyz", "0.4", "0", "0.2", "--export", "out"],
     "InvalidInputError: --zyz: a pose needs both the position and the Eq 42 angles; give --zyz too"),
])
def test_the_command_line_shows_its_options(capsys, argv, shown):
    assert main(argv) == 2
    assert capsys.readouterr().err.strip() == f"iik {argv[0]}: error: {shown}"
