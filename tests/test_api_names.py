"""The library's names for what the command line spells otherwise: a keyword in the
option's spelling is refused with one line that names the function's own keyword."""

from __future__ import annotations

import pytest

from impactcli import InputError, damped_impact
from impactcli.batch import batch_damped_impacts
from impactcli.impact import Sphere
from impactcli.validation import input_errors

STEEL = Sphere(0.02, 210e9, 0.3, 7800.0), Sphere(0.04, 210e9, 0.3, 7800.0)


def test_e_as_a_keyword_says_to_give_restitution():
    # damped_impact(..., e=0.8) said only "unexpected keyword argument 'e'", though the
    # command line's --e is its restitution=.
    with pytest.raises(InputError) as caught:
        damped_impact(*STEEL, 0.25, 0.75, "tsuji", e=0.8)
    message = str(caught.value)
    assert "unexpected keyword argument 'e'" in message and "give restitution=" in message
    assert "\n" not in message
    # what it says to give is the target e, reached
    result = damped_impact(*STEEL, 0.25, 0.75, "tsuji", restitution=0.8)
    assert result.summary["restitution"] == pytest.approx(0.8, abs=1e-9)
    with pytest.raises(InputError, match="give restitution="):
        batch_damped_impacts(0.02, 0.04, 0.25, 0.75, 210e9, 0.3, 210e9, 0.3, 7800.0, 7800.0,
                             damping="tsuji", e=0.8)  # fmt: skip


def test_only_the_call_of_the_function_itself_gets_the_hint():
    # an unknown 'e' of a call below the public function is that call's fault, not the
    # caller's; a function without restitution= has no such keyword to offer
    def below(restitution=None):
        return restitution

    @input_errors
    def public(restitution=None):
        return below(e=restitution)

    @input_errors
    def other(alpha=None):
        return alpha

    with pytest.raises(InputError) as caught:
        public(0.5)
    assert "give restitution=" not in str(caught.value)
    with pytest.raises(InputError) as caught:
        other(e=0.5)
    assert "unexpected keyword argument 'e'" in str(caught.value)
    assert "restitution" not in str(caught.value)
