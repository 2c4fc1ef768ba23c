"""Heidenhain Q-parameter formulas compiled once into closures (the formula evaluator of
:meth:`interpolators.heidenhain_params.QParameters.evaluate`).

A program that loops (``LBL 2`` ... ``FN 12: IF +Q4 LT +18,85 GOTO LBL 2``) evaluates the same formula
text tens of thousands of times. :func:`compile_formula` turns the token list of a formula into a tree
of closures once by recursive descent (``+ -`` over ``* / %`` over ``^``, right-associative, over unary
signs and functions, over numbers, parameters and parentheses); each evaluation then only reads the Q
parameters and computes, left to right within a level.

Errors that depend on the values (division by zero, a function or power outside its domain) are
raised during the evaluation through the context's ``fail``.

``a % b`` is the modulo value, the division remainder (iTNC 530 user's manual 60642x-04, 9.8 "Entering formulas
directly": "Calculate modulo value (division remainder) Example: Q12 = 400 % 360 Result: Q12 = 40"; the same in
the TNC 320 and TNC 620 manuals). Our reading: it binds as ``*`` and ``/`` do (the manuals give no precedence),
the remainder takes the sign of the dividend (``math.fmod``: the manuals give no negative example), and a
modulo by 0 is an error as a division by 0 is. A formula that does not parse raises
:class:`FormulaSyntaxError` naming what is wrong (a missing operand or ``)``, an unknown function, an
unexpected token), once, when it is compiled.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Protocol

__all__ = ["FormulaContext", "Compiled", "FormulaSyntaxError", "compile_formula"]


class FormulaContext(Protocol):
    """What a compiled formula reads and reports through: the Q-parameter store and ``fail``."""

    params: object

    def fail(self, why: str) -> None:
        """Raise the reader's error for ``why``, naming the formula (never returns)."""


#: A compiled formula: its value in a context.
Compiled = Callable[[FormulaContext], float]


class FormulaSyntaxError(Exception):
    """The token list is not a formula; the message says why (``missing operand``, ...)."""


class _Compiler:
    def __init__(self, tokens: list[tuple[str, str]], functions: dict[str, Callable[[float], float]]) -> None:
        self.tokens, self.functions, self.i = tokens, functions, 0

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def expression(self) -> Compiled:
        first, rest = self.term(), []
        while (t := self.peek()) is not None and t[1] in "+-" and t[0] == "op":
            self.i += 1
            rest.append((t[1] == "+", self.term()))
        if not rest:
            return first

        def run(ctx: FormulaContext) -> float:
            value = first(ctx)
            for plus, g in rest:
                rhs = g(ctx)
                value = value + rhs if plus else value - rhs
            return value
        return run

    def term(self) -> Compiled:
        first, rest = self.power(), []
        while (t := self.peek()) is not None and t[0] == "op" and t[1] in "*/%":
            self.i += 1
            start = self.i
            operand = self.power()
            rest.append((t[1], operand, " ".join(text for _, text in self.tokens[start:self.i])))
        if not rest:
            return first

        def run(ctx: FormulaContext) -> float:
            value = first(ctx)
            for op, g, text in rest:
                rhs = g(ctx)
                if op == "*":
                    value = value * rhs
                    continue
                if rhs == 0:  # the divisor named: a Q parameter of 0 is often an unset tool or table value
                    ctx.fail(f"{'division' if op == '/' else 'modulo'} by zero ({text} is 0)")
                value = value / rhs if op == "/" else math.fmod(value, rhs)
            return value
        return run

    def power(self) -> Compiled:
        base = self.unary()
        if self.peek() != ("op", "^"):
            return base
        self.i += 1
        exponent = self.power()

        def run(ctx: FormulaContext) -> float:
            b = base(ctx)
            e = exponent(ctx)
            try:
                return math.pow(b, e)
            except (ValueError, OverflowError):
                ctx.fail(f"{b!r} ^ {e!r} is undefined")
        return run

    def unary(self) -> Compiled:
        t = self.peek()
        if t is None:
            raise FormulaSyntaxError("missing operand")
        if t[0] == "op" and t[1] in "+-":
            self.i += 1
            inner = self.unary()
            return (lambda ctx: -inner(ctx)) if t[1] == "-" else inner
        if t[0] == "name":
            self.i += 1
            if t[1] == "PI":
                return lambda ctx: math.pi
            fn = self.functions.get(t[1])
            if fn is None:
                raise FormulaSyntaxError(f"unknown function {t[1]!r}")
            arg, name = self.unary(), t[1]

            def run(ctx: FormulaContext) -> float:
                a = arg(ctx)
                try:
                    return float(fn(a))
                except (ValueError, OverflowError):
                    ctx.fail(f"{name} of {a!r} is undefined")
            return run
        return self.primary()

    def primary(self) -> Compiled:
        t = self.peek()
        if t is None:
            raise FormulaSyntaxError("missing operand")
        self.i += 1
        if t[0] == "num":
            value = float(t[1])
            return lambda ctx: value
        if t[0] == "q":
            name = t[1]
            return lambda ctx: ctx.params.get(name)
        if t == ("op", "("):
            inner = self.expression()
            if self.peek() != ("op", ")"):
                raise FormulaSyntaxError("missing ')'")
            self.i += 1
            return inner
        raise FormulaSyntaxError(f"unexpected {t[1]!r}")


def compile_formula(tokens: list[tuple[str, str]],
                    functions: dict[str, Callable[[float], float]]) -> Compiled:
    """The closure computing the formula of ``tokens`` (``(kind, TEXT)`` pairs: ``num``, ``q``, ``name``,
    ``op``), with ``functions`` the named functions.

    Raises
    ------
    FormulaSyntaxError
        The tokens are no formula, or nest deeper than Python's recursion follows.
    """
    compiler = _Compiler(tokens, functions)
    try:
        run = compiler.expression()
    except RecursionError:  # thousands of nested parentheses, functions or signs: no TNC formula nests so
        raise FormulaSyntaxError(f"nested deeper than this reader follows ({len(tokens)} tokens)") from None
    if compiler.i != len(tokens):
        raise FormulaSyntaxError("unexpected " + repr(tokens[compiler.i][1]))
    return run
