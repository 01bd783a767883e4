"""The text's own cross-references: tables, figures, sections, equations and points it cites.

Each slip is a citation whose target, by the thesis's own List of Figures, List of Tables,
Table of Contents or equation numbering, is not what the sentence describes. The
sentences and captions are quoted from the thesis text (copied here; the project does
not read the thesis at run time).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..registry import Erratum, Row, Section, Verdict
from ..second_reading import numbering_slips, search

SECTION = Section("The text (cross-references)", depends_on=("text",))


@dataclass(frozen=True)
class Slip:
    """A cross-reference: where, what the text cites, what that target is, and the right target; ``cite``
    is the cited number, letters or pair of names (as printed, as it should be); the second reading tries
    the citations one number or letter off."""

    where: str
    quote: str
    cited_is: str
    correct: str
    cite: tuple = (None, None)

    def row(self, id: str) -> Row:
        """The citation's erratum row (``id``), after the second reading."""
        cited = f"cited target: {self.cited_is}"
        erratum = Erratum(f"{self.where} (citation)", self.quote, self.correct, cited)
        return Row(f"{self.where}: '{self.quote}'", f"{self.where} (citation)", "", f"{cited}; described: "
                   f"{self.correct}", Verdict.ERRATUM, id=id, errata=(erratum,)).reread(self.reading())

    def reading(self):
        """Second reading: is the right target one number or letter off the printed one (a typo)?"""
        cited, right = self.cite
        return search({"cite": cited}, numbering_slips("cite", cited, "the citation"),
                      lambda x: 0.0 if x["cite"] == right else 1.0, 0.0, printed=self.quote,
                      stated_text=f"the sentence describes {self.correct}",
                      route="the thesis's List of Figures, List of Tables, Table of Contents, equation "
                      "numbering and reference list",
                      measure="the cited target differs from the described one (0 = same)")


#: The slips found by reading each citation against the thesis's lists (captions quoted from them).
SLIPS = (
    Slip(
        "Sec 3.3.1 (after Eq 9)",
        "the offset links parameters from table I",
        "Table I: 'The 6-DOF robotic arm joint limits'",
        "Table II (Denavit-Hartenberg parameters: l2, l3, l4)",
        (1, 2),
    ),
    Slip(
        "Sec 3.3.2",
        "Using the Law of Cosines on the triangle formed by A, B and C in figure 9a",
        "A is the base; Eq 14 relates |D - B|, l3 = |BC| and l4 = |CD| (rows ik.eq14, ik.eq7)",
        "the triangle formed by B, C and D",
        ("ABC", "BCD"),
    ),
    Slip(
        "Sec 3.3.3",
        "x_D, y_D and z_D parameters, are known from Equation 9b",
        "Eq 9b gives y_D only",
        "Equations 9a-9c",
        ("9b", "9a-9c"),
    ),
    Slip(
        "Sec 3.4.3",
        "The complete analysis ... for two sample points ... is presented in Appendix E",
        "Appendix E analyses three points (A1, A2, A6)",
        "three sample points",
        (2, 3),
    ),
    Slip(
        "Sec 3.4.3",
        "s(2) = [theta1 = 160, theta3 = 90, theta5 = 0]; s(3) = [theta1 = -160, ...]",
        "Table VI and App. E list s(2) with theta1 = -160 deg and s(3) with +160 deg",
        "s(2) with theta1 = -160 deg, s(3) with +160 deg (or swap the names in Table VI)",
        (("s(2)", "s(3)"), ("s(3)", "s(2)")),
    ),
    Slip(
        "Sec 3.5.3.2",
        "links 3 and 4 required to be completely contracted as shown in Figure 4a",
        "Figure 4: 'Workspace of the manipulator' (it has no part a)",
        "Figure 26 ('Configuration with maximum alpha orientation and links 3 and 4 contracted')",
        (4, 26),
    ),
    Slip(
        "Sec 4.2.1.1",
        "the index presented in Figure 27 represents the CPU cycles required for each method",
        "Figure 27: 'Ellipsoid boundary enclosing a rectangular prism obstacle'",
        "Figure 33 ('The first predefined path computational efforts')",
        (27, 33),
    ),
    Slip(
        "Sec 4.2.1.3",
        "Figures 32 to 35 show the representation of the path ... for the third predefined path",
        "Figures 32-35 belong to paths 1 and 2 (Fig 32: effort index of path 1; Figs 33-35: path 2)",
        "Figures 38 to 41",
        (32, 38),
    ),
    Slip(
        "Sec 4.3",
        "Each scenario was properly set (Figure 45) to mimic the simulations presented in Section 4.1",
        "Section 4.1 is the chapter's introduction",
        "Section 4.2 (Simulation Results)",
        (1, 2),
    ),
    Slip(
        "App. A",
        "the commands were selected from the programming guide [19] provided by the manipulator manufacturer",
        "[19] is 'MathWorks, Matlab Documentation Center: ellipsoid', which Eq 52 cites correctly",
        "[20] (Schunk, Amtec Robotics - Programmers guide for PowerCube, Version 1.3, 2007)",
        (19, 20),
    ),
    Slip(
        "App. G",
        "As discussed in Section 5.2, the graphical interface can be enhanced by implementing a real time "
        "visual sensor",
        "Section 5.2 holds the conclusions",
        "Section 5.3 (Recommendations, item 1)",
        (2, 3),
    ),
)


@SECTION.check(
    990.0,
    by_construction="a reading of each citation against the thesis's own lists of figures and tables, table "
    "of contents and equation numbering (quoted in verification/checks/text.py); no computation",
)
def cross_references(ctx):
    """The cross-reference slips of the text, one erratum record each."""
    details = tuple(s.row(f"c{k + 1}") for k, s in enumerate(SLIPS))
    return Row.grouped(
        "The tables, figures, sections, equations, points and references the text cites are the ones it "
        "describes.",
        "Cross-references (whole text)",
        "every numbered citation read against the List of Figures, List of Tables, Table of Contents and "
        "equation numbering of the thesis and its reference list",
        "; ".join(f"{s.where}: '{s.quote}' -> {s.correct}" for s in SLIPS),
        details,
        "citations whose target is not what the sentence describes",
        fail=Verdict.ERRATUM,
        id="cross_references",
        covers=("Cross-references",),
        domain=f"the {len(SLIPS)} citations found wrong by reading every numbered citation",
    )
