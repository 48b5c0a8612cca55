//! The expression language of user-defined effects, compiled once to a small stack program.
//!
//! Size: the grammar, its compiler and evaluator, and the tests that pin each limit (length,
//! nesting, operations, stack, constants) belong together.
//!
//! ```text
//! expr    := term (('+' | '-') term)*
//! term    := unary (('*' | '/') unary)*
//! unary   := '-' unary | power
//! power   := primary ('^' unary)?            right-associative: a^b^c = a^(b^c), -x^2 = -(x^2)
//! primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
//! ```
//!
//! Functions: `exp ln sqrt abs` (one argument), `min max` (two). Names are resolved when the
//! expression is compiled (by the caller, who knows which variables a quantity may read), so an
//! unknown name is an error at load time, never at evaluation.
//!
//! A [`Program`] is a fixed-size array of postfix operations with a stack depth checked at
//! compile time: evaluating it ([`Program::eval`]) touches only a fixed-size stack array, never
//! the heap, and is generic over [`Real`], so the same compiled program runs in the scalar solve
//! and on the face-map kernel's lanes. Arithmetic is IEEE-754 `+ − × ÷`; `^` is libm `pow`
//! (lane by lane), so `cor * (u1n_m_s / 48.77) ^ (-q)` gives the same bits as the library's
//! `cor_power` law.
//!
//! Why not a crate: the maintained expression crates (`evalexpr`, `meval`, `fasteval`) evaluate
//! on `f64` only, and most allocate per evaluation (boxed trees, string-keyed contexts); the
//! kernel needs the same program on a vector of lanes. The grammar above is ~200 lines.

use super::real::Real;

/// Most operations in one compiled expression.
pub const MAX_OPS: usize = 64;

/// Deepest evaluation stack an expression may need.
pub const MAX_STACK: usize = 16;

/// Deepest nesting of parentheses, function calls, signs and powers the parser follows. Every
/// nesting level costs a frame of the recursive parser; checked before recursing, so that a
/// hostile `((((…` or `-----…` 20 000 deep is an error, not a stack overflow. An expression
/// nested deeper than it has operations ([`MAX_OPS`]) is never needed.
pub const MAX_NEST: usize = MAX_OPS;

/// Longest expression text, characters, checked before the text is tokenized. [`MAX_OPS`]
/// operations with names of 40 characters and spaces fit in about 3 000.
pub const MAX_CHARS: usize = 4096;

/// One postfix operation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Op {
    /// Push a constant.
    Const(f64),
    /// Push variable number `i`.
    Var(u8),
    /// Negate the top.
    Neg,
    /// `a + b`.
    Add,
    /// `a − b`.
    Sub,
    /// `a × b`.
    Mul,
    /// `a ÷ b`.
    Div,
    /// `a^b` (libm `pow`).
    Pow,
    /// `exp(a)`.
    Exp,
    /// `ln(a)`.
    Ln,
    /// `√a`.
    Sqrt,
    /// `|a|`.
    Abs,
    /// `min(a, b)`.
    Min,
    /// `max(a, b)`.
    Max,
}

/// A compiled expression: postfix operations over numbered variables. `Copy`, no heap.
#[derive(Clone, Copy, PartialEq)]
pub struct Program {
    ops: [Op; MAX_OPS],
    len: u8,
    /// Bit `i` set: the program reads variable `i` (variables are numbered below 64).
    reads: u64,
}

impl std::fmt::Debug for Program {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.ops()).finish()
    }
}

/// Why an expression does not compile: what is wrong, at which character (1-based column).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExprError {
    /// 1-based column (in characters) in the expression.
    pub column: usize,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl Program {
    /// The operations, in order.
    pub fn ops(&self) -> &[Op] {
        &self.ops[..self.len as usize]
    }

    /// Does the program read variable `i`?
    pub fn reads(&self, i: u8) -> bool {
        self.reads & (1 << i) != 0
    }

    /// Every variable it reads: bit `i` for variable `i`.
    pub fn read_mask(&self) -> u64 {
        self.reads
    }

    /// Compile `text`; `resolve` maps a name to its variable number (< 64) or says why the name
    /// is not allowed here.
    pub fn compile<E: std::fmt::Display>(
        text: &str,
        resolve: &dyn Fn(&str) -> Result<u8, E>,
    ) -> Result<Self, ExprError> {
        let n_chars = text.chars().count();
        if n_chars > MAX_CHARS {
            return Err(ExprError {
                column: MAX_CHARS + 1,
                message: format!("expression too long ({n_chars} characters; at most {MAX_CHARS})"),
            });
        }
        let tokens = tokenize(text)?;
        let mut p = Parser {
            tokens: &tokens,
            pos: 0,
            end_column: text.chars().count() + 1,
            out: Program {
                ops: [Op::Const(0.0); MAX_OPS],
                len: 0,
                reads: 0,
            },
            depth: 0,
            nest: 0,
            resolve,
        };
        p.expr()?;
        if let Some(t) = p.tokens.get(p.pos) {
            return Err(ExprError {
                column: t.column,
                message: format!("unexpected {} after a complete expression", t.kind.show()),
            });
        }
        Ok(p.out)
    }

    /// Evaluate on variables `vars` (indexed as at compile time). No allocation. Always
    /// inlined: on the fits' lanes it runs inside a `#[target_feature]` function, whose
    /// instruction set only inlined code shares.
    #[inline(always)]
    pub fn eval<R: Real>(&self, vars: &[R]) -> R {
        let mut stack = [R::splat(0.0); MAX_STACK];
        let mut sp = 0usize;
        for op in self.ops() {
            match *op {
                Op::Const(c) => {
                    stack[sp] = R::splat(c);
                    sp += 1;
                }
                Op::Var(i) => {
                    stack[sp] = vars[i as usize];
                    sp += 1;
                }
                Op::Neg => stack[sp - 1] = -stack[sp - 1],
                Op::Exp => stack[sp - 1] = stack[sp - 1].map(f64::exp),
                Op::Ln => stack[sp - 1] = stack[sp - 1].map(f64::ln),
                Op::Sqrt => stack[sp - 1] = stack[sp - 1].sqrt(),
                Op::Abs => stack[sp - 1] = stack[sp - 1].map(f64::abs),
                binary => {
                    sp -= 1;
                    let (a, b) = (stack[sp - 1], stack[sp]);
                    stack[sp - 1] = match binary {
                        Op::Add => a + b,
                        Op::Sub => a - b,
                        Op::Mul => a * b,
                        Op::Div => a / b,
                        Op::Pow => a.zip_map(b, f64::powf),
                        Op::Min => a.zip_map(b, f64::min),
                        _ => a.zip_map(b, f64::max),
                    };
                }
            }
        }
        stack[0]
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Name(String),
    Sym(char),
}

impl Tok {
    fn show(&self) -> String {
        match self {
            Tok::Num(v) => format!("number {v}"),
            Tok::Name(n) => format!("name '{n}'"),
            Tok::Sym(c) => format!("'{c}'"),
        }
    }
}

struct Token {
    kind: Tok,
    column: usize,
}

fn tokenize(text: &str) -> Result<Vec<Token>, ExprError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // Exponent: 1e-3, 2.5E+2.
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    i = j;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let s: String = chars[start..i].iter().collect();
            let v: f64 = s.parse().map_err(|_| ExprError {
                column,
                message: format!("'{s}' is not a number"),
            })?;
            if !v.is_finite() {
                return Err(ExprError {
                    column,
                    message: format!(
                        "the number {s} is beyond the largest a double can hold (about \
                         1.8e308); write a finite constant"
                    ),
                });
            }
            out.push(Token {
                kind: Tok::Num(v),
                column,
            });
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Token {
                kind: Tok::Name(chars[start..i].iter().collect()),
                column,
            });
        } else if "+-*/^(),".contains(c) {
            out.push(Token {
                kind: Tok::Sym(c),
                column,
            });
            i += 1;
        } else {
            return Err(ExprError {
                column,
                message: format!(
                    "unexpected character '{c}'; allowed: numbers, names, + - * / ^ ( ) ,"
                ),
            });
        }
    }
    Ok(out)
}

/// Functions: name, number of arguments, operation.
const FUNCTIONS: [(&str, usize, Op); 6] = [
    ("exp", 1, Op::Exp),
    ("ln", 1, Op::Ln),
    ("sqrt", 1, Op::Sqrt),
    ("abs", 1, Op::Abs),
    ("min", 2, Op::Min),
    ("max", 2, Op::Max),
];

/// A name a fixed vocabulary does not have (a resolver for [`Program::compile`] whose names are
/// the program's own, such as a library effect's law).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown name '{0}'")]
pub struct UnknownName(pub String);

struct Parser<'a, E> {
    tokens: &'a [Token],
    pos: usize,
    end_column: usize,
    out: Program,
    depth: usize,
    /// Current recursion depth of [`Parser::unary`], through which every nesting passes.
    nest: usize,
    resolve: &'a dyn Fn(&str) -> Result<u8, E>,
}

impl<E: std::fmt::Display> Parser<'_, E> {
    fn column(&self) -> usize {
        self.tokens
            .get(self.pos)
            .map_or(self.end_column, |t| t.column)
    }

    fn peek_sym(&self, c: char) -> bool {
        matches!(self.tokens.get(self.pos), Some(Token { kind: Tok::Sym(s), .. }) if *s == c)
    }

    fn emit(&mut self, op: Op, column: usize) -> Result<(), ExprError> {
        if self.out.len as usize == MAX_OPS {
            return Err(ExprError {
                column,
                message: format!("expression too long (more than {MAX_OPS} operations)"),
            });
        }
        match op {
            Op::Const(_) | Op::Var(_) => self.depth += 1,
            Op::Neg | Op::Exp | Op::Ln | Op::Sqrt | Op::Abs => {}
            _ => self.depth -= 1,
        }
        if self.depth > MAX_STACK {
            return Err(ExprError {
                column,
                message: format!(
                    "expression nested too deeply (more than {MAX_STACK} pending values)"
                ),
            });
        }
        self.out.ops[self.out.len as usize] = op;
        self.out.len += 1;
        Ok(())
    }

    fn expr(&mut self) -> Result<(), ExprError> {
        self.term()?;
        loop {
            let column = self.column();
            let op = if self.peek_sym('+') {
                Op::Add
            } else if self.peek_sym('-') {
                Op::Sub
            } else {
                return Ok(());
            };
            self.pos += 1;
            self.term()?;
            self.emit(op, column)?;
        }
    }

    fn term(&mut self) -> Result<(), ExprError> {
        self.unary()?;
        loop {
            let column = self.column();
            let op = if self.peek_sym('*') {
                Op::Mul
            } else if self.peek_sym('/') {
                Op::Div
            } else {
                return Ok(());
            };
            self.pos += 1;
            self.unary()?;
            self.emit(op, column)?;
        }
    }

    /// Every recursion of the parser (parentheses, function arguments, signs, exponents) passes
    /// here, so the nesting is bounded here, before recursing.
    fn unary(&mut self) -> Result<(), ExprError> {
        if self.nest == MAX_NEST {
            return Err(ExprError {
                column: self.column(),
                message: format!(
                    "expression nested too deeply (more than {MAX_NEST} levels of parentheses, \
                     function calls, signs or powers)"
                ),
            });
        }
        self.nest += 1;
        let result = self.unary_inner();
        self.nest -= 1;
        result
    }

    fn unary_inner(&mut self) -> Result<(), ExprError> {
        let column = self.column();
        if self.peek_sym('-') {
            self.pos += 1;
            self.unary()?;
            return self.emit(Op::Neg, column);
        }
        if self.peek_sym('+') {
            self.pos += 1;
            return self.unary();
        }
        self.power()
    }

    fn power(&mut self) -> Result<(), ExprError> {
        self.primary()?;
        let column = self.column();
        if self.peek_sym('^') {
            self.pos += 1;
            self.unary()?;
            self.emit(Op::Pow, column)?;
        }
        Ok(())
    }

    fn expect(&mut self, c: char, what: &str) -> Result<(), ExprError> {
        if self.peek_sym(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(ExprError {
                column: self.column(),
                message: match self.tokens.get(self.pos) {
                    Some(t) => format!("expected {what}, found {}", t.kind.show()),
                    None => format!("expected {what}, found the end of the expression"),
                },
            })
        }
    }

    fn primary(&mut self) -> Result<(), ExprError> {
        let column = self.column();
        let Some(tok) = self.tokens.get(self.pos) else {
            return Err(ExprError {
                column,
                message: "expected a number, a name or '(', found the end of the expression".into(),
            });
        };
        match &tok.kind {
            Tok::Num(v) => {
                self.pos += 1;
                self.emit(Op::Const(*v), column)
            }
            Tok::Sym('(') => {
                self.pos += 1;
                self.expr()?;
                self.expect(')', "')'")
            }
            Tok::Name(name) => {
                self.pos += 1;
                if self.peek_sym('(') {
                    let Some(&(_, arity, op)) = FUNCTIONS.iter().find(|f| f.0 == name) else {
                        return Err(ExprError {
                            column,
                            message: format!(
                                "unknown function '{name}'; functions: exp, ln, sqrt, abs (one \
                                 argument), min, max (two)"
                            ),
                        });
                    };
                    self.pos += 1;
                    for k in 0..arity {
                        if k > 0 {
                            self.expect(',', &format!("',' ({name} takes {arity} arguments)"))?;
                        }
                        self.expr()?;
                    }
                    self.expect(')', &format!("')' ({name} takes {arity} argument(s))"))?;
                    return self.emit(op, column);
                }
                if FUNCTIONS.iter().any(|f| f.0 == name) {
                    return Err(ExprError {
                        column,
                        message: format!("'{name}' is a function: write {name}(…)"),
                    });
                }
                let var = (self.resolve)(name).map_err(|e| ExprError {
                    column,
                    message: e.to_string(),
                })?;
                debug_assert!(var < 64);
                self.out.reads |= 1 << var;
                self.emit(Op::Var(var), column)
            }
            other => Err(ExprError {
                column,
                message: format!("expected a number, a name or '(', found {}", other.show()),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::V;

    fn vars(name: &str) -> Result<u8, UnknownName> {
        match name {
            "x" => Ok(0),
            "y" => Ok(1),
            "q" => Ok(2),
            "u1n_m_s" => Ok(3),
            _ => Err(UnknownName(name.to_owned())),
        }
    }

    fn eval(text: &str, v: &[f64]) -> f64 {
        Program::compile(text, &vars).unwrap().eval(v)
    }

    #[test]
    fn precedence_and_associativity() {
        let v = [2.0, 3.0, 0.5, 48.77];
        assert_eq!(eval("1 + 2 * 3", &v), 7.0);
        assert_eq!(eval("(1 + 2) * 3", &v), 9.0);
        assert_eq!(eval("x - y - 1", &v), -2.0);
        assert_eq!(eval("x / y / 2", &v), 2.0 / 3.0 / 2.0);
        assert_eq!(eval("2 ^ 3 ^ 2", &v), 512.0);
        assert_eq!(eval("-x ^ 2", &v), -4.0);
        assert_eq!(eval("x ^ -1", &v), 0.5);
        assert_eq!(eval("--x", &v), 2.0);
        assert_eq!(eval("+x", &v), 2.0);
        assert_eq!(eval("1.5e2 + 2E-1 + .5", &v), 150.7);
        assert_eq!(eval("min(x, y) + max(x, y)", &v), 5.0);
        assert_eq!(eval("abs(-y) + sqrt(4) + exp(0) + ln(1)", &v), 6.0);
    }

    #[test]
    fn same_bits_as_the_library_power_law() {
        // The library's cor_power: (u1n/48.77).powf(-q) * cor.
        let p = Program::compile("x * (u1n_m_s / 48.77) ^ (-q)", &vars).unwrap();
        for u in [30.0, 41.3, 48.77, 55.1] {
            let v = [0.83, 0.0, 0.12, u];
            let lib = (u / 48.77f64).powf(-0.12) * 0.83;
            assert_eq!(p.eval(&v).to_bits(), lib.to_bits());
        }
    }

    #[test]
    fn lanes_and_scalars_agree_bit_for_bit() {
        let p = Program::compile(
            "exp(-x * y) + ln(q) * max(u1n_m_s, 40) ^ 0.3 - abs(x)",
            &vars,
        )
        .unwrap();
        let lanes = [
            V([0.1, 0.2, 0.3, 0.4]),
            V([1.0, -2.0, 3.0, 0.5]),
            V([0.5, 0.7, 1.5, 2.0]),
            V([35.0, 45.0, 50.0, 60.0]),
        ];
        let got = p.eval(&lanes);
        for i in 0..4 {
            let s = [lanes[0].0[i], lanes[1].0[i], lanes[2].0[i], lanes[3].0[i]];
            assert_eq!(got.0[i].to_bits(), p.eval(&s).to_bits());
        }
    }

    #[test]
    fn reads_records_the_variables_used() {
        let p = Program::compile("x * (u1n_m_s / 48.77) ^ (-q)", &vars).unwrap();
        assert!(p.reads(0) && p.reads(2) && p.reads(3) && !p.reads(1));
    }

    fn err(text: &str) -> ExprError {
        Program::compile(text, &vars).unwrap_err()
    }

    #[test]
    fn errors_name_the_column() {
        let e = err("x * (y + 1");
        assert_eq!(e.column, 11, "{e:?}");
        assert!(e.message.contains("expected ')'"), "{e:?}");
        let e = err("x + zz");
        assert_eq!((e.column, e.message.as_str()), (5, "unknown name 'zz'"));
        let e = err("x $ y");
        assert_eq!(e.column, 3);
        assert!(e.message.contains("unexpected character '$'"));
        let e = err("x y");
        assert_eq!(e.column, 3);
        assert!(e.message.contains("unexpected name 'y'"), "{e:?}");
        let e = err("foo(x)");
        assert_eq!(e.column, 1);
        assert!(e.message.contains("unknown function 'foo'"));
        let e = err("min(x)");
        assert!(e.message.contains("','"), "{e:?}");
        let e = err("exp + 1");
        assert!(e.message.contains("is a function"), "{e:?}");
        let e = err("");
        assert_eq!(e.column, 1);
        let e = err("x *");
        assert_eq!(e.column, 4);
        let e = err("1..2");
        assert!(e.message.contains("not a number"), "{e:?}");
        let e = err(")");
        assert!(e.message.contains("found ')'"), "{e:?}");
    }

    #[test]
    fn limits_are_errors_not_panics() {
        let long = vec!["x"; MAX_OPS].join(" + ");
        assert!(err(&long).message.contains("too long"));
        let deep = format!(
            "{}x{}",
            "(x + ".repeat(MAX_STACK + 2),
            ")".repeat(MAX_STACK + 2)
        );
        assert!(err(&deep).message.contains("nested too deeply"));
        // Nesting far beyond the limits is an error found before recursing (no stack overflow).
        for open in ["(", "abs(", "-", "+", "2^"] {
            // Deeper than the nesting limit within the length limit: refused by nesting.
            let text = format!("{}x", open.repeat(4 * MAX_NEST));
            let e = err(&text);
            assert!(e.message.contains("nested too deeply"), "{open}: {e:?}");
            // 20 000 deep: refused by its length before it is tokenized.
            let text = format!("{}x", open.repeat(20_000));
            let e = err(&text);
            assert!(e.message.contains("too long"), "{open}: {e:?}");
        }
        let e = err(&"x+".repeat(3000));
        assert!(e.message.contains("too long (6000 characters"), "{e:?}");
        let e = err("1e400 * x");
        assert_eq!(e.column, 1);
        assert!(e.message.contains("1e400 is beyond"), "{e:?}");
        // Just within the limits compiles and evaluates.
        let ok = format!(
            "{}x{}",
            "(x + ".repeat(MAX_STACK - 2),
            ")".repeat(MAX_STACK - 2)
        );
        assert_eq!(eval(&ok, &[1.0, 0.0, 0.0, 0.0]), (MAX_STACK - 1) as f64);
    }
}
