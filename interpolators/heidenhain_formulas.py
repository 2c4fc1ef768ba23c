"""Heidenhain Q-parameter formulas compiled once into closures (the speed layer of the formula evaluator).

A program that loops (``LBL 2`` ... ``FN 12: IF +Q4 LT +18,85 GOTO LBL 2``) evaluates the same formula
text tens of thousands of times. :func:`compile_formula` turns the token list of a formula into a tree
of closures once; each evaluation then only reads the Q parameters and computes, in the same order
and with the same arithmetic as the recursive-descent evaluator of
:mod:`interpolators.heidenhain_params` (whose grammar this mirrors: ``+ -`` over ``* /`` over ``^``,
right-associative, over unary signs and functions, over numbers, parameters and parentheses).

Errors that depend on the values (division by zero, a function or power outside its domain) are
raised during the evaluation through the context's ``fail``, as the evaluator raises them. A formula
that does not parse is not compiled (``None``): the caller then runs the evaluator, which raises the
syntax error exactly where it always did.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Protocol

__all__ = ["FormulaContext", "Compiled", "compile_formula"]


class FormulaContext(Protocol):
    """What a compiled formula reads and reports through: the Q-parameter store and ``fail``."""

    params: object

    def fail(self, why: str) -> None:
        """Raise the evaluator's error for ``why`` (never returns)."""


#: A compiled formula: its value in a context.
Compiled = Callable[[FormulaContext], float]


class _Unparsable(Exception):
    """The token list is not a formula (the evaluator reports why)."""


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
        while (t := self.peek()) is not None and t[0] == "op" and t[1] in "*/":
            self.i += 1
            rest.append((t[1] == "/", self.power()))
        if not rest:
            return first

        def run(ctx: FormulaContext) -> float:
            value = first(ctx)
            for divide, g in rest:
                rhs = g(ctx)
                if divide:
                    if rhs == 0:
                        ctx.fail("division by zero")
                    value = value / rhs
                else:
                    value = value * rhs
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
            raise _Unparsable
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
                raise _Unparsable
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
            raise _Unparsable
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
                raise _Unparsable
            self.i += 1
            return inner
        raise _Unparsable


def compile_formula(tokens: list[tuple[str, str]],
                    functions: dict[str, Callable[[float], float]]) -> Compiled | None:
    """The closure computing the formula of ``tokens`` (``(kind, TEXT)`` pairs: ``num``, ``q``, ``name``,
    ``op``), with ``functions`` the named functions; ``None`` when the tokens are no formula."""
    compiler = _Compiler(tokens, functions)
    try:
        run = compiler.expression()
    except (_Unparsable, RecursionError):
        return None
    return run if compiler.i == len(tokens) else None
