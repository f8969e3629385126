//! Macro variables and expressions: Fanuc Macro B (local, common and system variables, the vacant
//! value) and LinuxCNC parameters, evaluated on an explicit stack so no chain overflows the stack.

use std::borrow::Cow;
use std::collections::HashMap;

use swarf_syntax::{BinOp, Diagnostic, Dialect, Expr, ExprId, ExprNode, Func, Program, Span};

/// A macro value: `None` is Fanuc's vacant ("null", #0), distinct from 0.
pub type Value = Option<f64>;

/// The system variables (#1000+, #2001…, #3000, #4001…, #5001…, #5221…), which the machine gives;
/// asked first for every number, so it may claim numbers in LinuxCNC's parameter range.
pub trait SystemVariables {
    /// `None` when `n` is not a system variable it knows, `Some(value)` otherwise.
    fn read(&self, n: u32) -> Option<Value>;

    /// `Err` for a read-only variable, `Ok(true)` when handled, `Ok(false)` if not one.
    fn write(&mut self, n: u32, v: Value) -> Result<bool, String>;
}

/// Local variables per call level (#1–#33; #1–#30 in LinuxCNC) and named locals.
#[derive(Debug, Clone)]
struct Frame {
    locals: [Value; FANUC_LOCALS],
    named: HashMap<Box<str>, f64>,
}

impl Frame {
    fn new(fill: Value) -> Self {
        Frame {
            locals: [fill; FANUC_LOCALS],
            named: HashMap::new(),
        }
    }
}

/// Fanuc local variables #1–#33 (LinuxCNC's subroutine parameters are #1–#30 of them).
const FANUC_LOCALS: usize = 33;
/// LinuxCNC numbered parameters are #1 up to `RS274NGC_MAX_PARAMETERS - 1`.
const LINUXCNC_PARAMETERS: u32 = 5602;
/// LinuxCNC compares `EQ`, `NE`, `LE`, `GE` with this tolerance (`TOLERANCE_EQUAL`).
const LINUXCNC_EQUAL: f64 = 1e-6;

/// The macro variable store: locals (a frame per call level), commons, and LinuxCNC's numbered and
/// named parameters; system variables come from a [`SystemVariables`].
#[derive(Debug, Clone)]
pub struct Variables {
    dialect: Dialect,
    /// The main program's level.
    main: Frame,
    /// The macro / o-word call levels entered, innermost last.
    calls: Vec<Frame>,
    /// Fanuc: #100–#199 then #500–#999; LinuxCNC: each parameter by its number. Grown as variables
    /// are set, so an unused store costs nothing.
    store: Vec<Value>,
    /// LinuxCNC global named parameters (`#<_name>`).
    globals: HashMap<Box<str>, f64>,
}

/// An empty store for the default dialect.
impl Default for Variables {
    fn default() -> Self {
        Variables::new(Dialect::default())
    }
}

impl Variables {
    /// An empty store for `dialect`: Fanuc-family variables vacant, LinuxCNC parameters 0.
    pub fn new(dialect: Dialect) -> Self {
        Variables {
            dialect,
            main: Frame::new(is_linuxcnc(dialect).then_some(0.0)),
            calls: Vec::new(),
            store: Vec::new(),
            globals: HashMap::new(),
        }
    }

    /// A variable's value before it is set: vacant in the Fanuc family, 0 in LinuxCNC.
    fn initial(&self) -> Value {
        is_linuxcnc(self.dialect).then_some(0.0)
    }

    /// Enters a call level (G65/G66, LinuxCNC o-word call) with (local number, value) arguments;
    /// other locals start as `Variables::initial`, numbers outside the local range are ignored.
    pub fn push_frame(&mut self, args: &[(u8, f64)]) {
        let mut frame = Frame::new(self.initial());
        for &(i, v) in args {
            // Local #i is at i - 1 (0 wraps round to no local).
            if let Some(slot) = frame.locals.get_mut(usize::from(i).wrapping_sub(1)) {
                *slot = Some(v);
            }
        }
        self.calls.push(frame);
    }

    /// Leaves the current call level (M99, `endsub`, `return`); the main level is never left.
    pub fn pop_frame(&mut self) {
        self.calls.pop();
    }

    /// The value of variable `n` (a computed whole number), asking `sys` first.
    pub fn get(&self, n: f64, sys: &dyn SystemVariables) -> Result<Value, String> {
        let n = self.number(n)?;
        if let Some(v) = sys.read(n) {
            return Ok(v);
        }
        if n == 0 && !is_linuxcnc(self.dialect) {
            return Ok(None);
        }
        match self.slot(n) {
            Some(Slot::Local(i)) => Ok(self.frame().locals.get(i).copied().flatten()),
            Some(Slot::Store(i)) => Ok(self.store.get(i).copied().unwrap_or(self.initial())),
            None => Err(self.missing(n)),
        }
    }

    /// Sets variable `n` to `v`: `sys` handles system variables; #0 cannot be assigned.
    pub fn set(&mut self, n: f64, v: Value, sys: &mut dyn SystemVariables) -> Result<(), String> {
        let n = self.number(n)?;
        if n == 0 && !is_linuxcnc(self.dialect) {
            return Err("#0 is always vacant and cannot be assigned".to_string());
        }
        if sys.write(n, v)? {
            return Ok(());
        }
        let slot = match self.slot(n) {
            Some(Slot::Local(i)) => self.frame_mut().locals.get_mut(i),
            Some(Slot::Store(i)) => {
                if self.store.len() <= i {
                    self.store.resize(i + 1, self.initial());
                }
                self.store.get_mut(i)
            }
            None => None,
        };
        let Some(slot) = slot else {
            return Err(self.missing(n));
        };
        *slot = v;
        Ok(())
    }

    /// The stored named parameter `name` (`_abc` global, `abc` local), `None` if not defined.
    pub fn get_named(&self, name: &str) -> Value {
        let name = lower(name);
        if name.starts_with('_') {
            self.globals.get(name.as_ref()).copied()
        } else {
            self.frame().named.get(name.as_ref()).copied()
        }
    }

    /// Stores `#<name>`: global when it starts with `_`, else local; `None` removes it.
    pub fn set_named(&mut self, name: &str, v: Value) {
        let name = lower(name);
        let map = if name.starts_with('_') {
            &mut self.globals
        } else {
            &mut self.frame_mut().named
        };
        if let Some(v) = v {
            map.insert(name.into_owned().into_boxed_str(), v);
        } else {
            map.remove(name.as_ref());
        }
    }

    fn frame(&self) -> &Frame {
        self.calls.last().unwrap_or(&self.main)
    }

    fn frame_mut(&mut self) -> &mut Frame {
        self.calls.last_mut().unwrap_or(&mut self.main)
    }

    /// Checks a computed variable number and makes it an integer.
    fn number(&self, n: f64) -> Result<u32, String> {
        let linuxcnc = is_linuxcnc(self.dialect);
        let tolerance = if linuxcnc { 1e-4 } else { 1e-6 };
        if !n.is_finite() {
            return Err(format!("variable number {n} is not a number"));
        }
        let r = n.round();
        if (n - r).abs() > tolerance {
            return Err(format!("variable number must be a whole number (#[{}])", n));
        }
        if r < 0.0 {
            return Err(format!("variable number must not be negative (#[{}])", n));
        }
        if r > f64::from(u32::MAX) {
            return Err(self.missing(r));
        }
        // In range and whole: the conversion is exact.
        Ok(r as u32)
    }

    /// Where variable `n` lives in the store, if it is one of the store's.
    fn slot(&self, n: u32) -> Option<Slot> {
        let n_usize = n as usize;
        if is_linuxcnc(self.dialect) {
            return match n {
                1..=30 => Some(Slot::Local(n_usize - 1)),
                _ if (31..LINUXCNC_PARAMETERS).contains(&n) => Some(Slot::Store(n_usize)),
                _ => None,
            };
        }
        match n {
            1..=33 => Some(Slot::Local(n_usize - 1)),
            // The common variables cleared at reset, then those kept through it and power-off.
            100..=199 => Some(Slot::Store(n_usize - 100)),
            500..=999 => Some(Slot::Store(n_usize - 400)),
            _ => None,
        }
    }

    fn missing(&self, n: impl std::fmt::Display) -> String {
        format!("variable #{n} does not exist on {}", self.dialect.label())
    }
}

#[derive(Debug, Clone, Copy)]
enum Slot {
    /// Index into the current frame's locals.
    Local(usize),
    /// Index into `store`.
    Store(usize),
}

fn is_linuxcnc(dialect: Dialect) -> bool {
    dialect == Dialect::LinuxCnc
}

fn lower(name: &str) -> Cow<'_, str> {
    if name.bytes().any(|b| b.is_ascii_uppercase()) {
        Cow::Owned(name.to_ascii_lowercase())
    } else {
        Cow::Borrowed(name)
    }
}

/// Fanuc argument specification I: the local variable a G65/G66 address letter sets (A→#1, B→#2,
/// C→#3, I→#4 … Z→#26); G, L, N, O and P are not arguments.
pub fn argument_variable(letter: u8) -> Option<u8> {
    // Each letter at its variable's place from #1; `_` where no letter sets the variable.
    const LETTERS: &[u8] = b"ABCIJKDEF_H_M___QRSTUVWXYZ";
    let letter = letter.to_ascii_uppercase();
    let i = LETTERS.iter().position(|&l| l == letter && l != b'_')?;
    u8::try_from(i + 1).ok()
}

/// Evaluates expression `id`: `Ok(None)` for a vacant variable read as it is.
pub fn eval(
    program: &Program,
    id: ExprId,
    vars: &Variables,
    sys: &dyn SystemVariables,
) -> Result<Value, Diagnostic> {
    Evaluator { program, vars, sys }.run(id)
}

/// The variable an assignment writes, once its number is computed.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// `#n` / `#[expr]`: the computed number (checked when the value is stored).
    Number(f64),
    /// LinuxCNC `#<name>` (lowercase).
    Named(Box<str>),
}

/// An assignment evaluated but not yet stored: LinuxCNC sets a line's parameters only after reading
/// the whole line, so each is prepared, then [`apply`](Assignment::apply)ed in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Assignment {
    /// Where the value goes.
    pub target: Target,
    /// The value (vacant stays vacant).
    pub value: Value,
    /// The target's text, for errors when storing.
    pub span: Span,
}

impl Assignment {
    /// Stores the value.
    pub fn apply(
        &self,
        vars: &mut Variables,
        sys: &mut dyn SystemVariables,
    ) -> Result<(), Diagnostic> {
        match &self.target {
            Target::Number(n) => vars
                .set(*n, self.value, sys)
                .map_err(|m| Diagnostic::error(self.span, "E-MACRO-VARIABLE", m)),
            Target::Named(name) => {
                vars.set_named(name, self.value);
                Ok(())
            }
        }
    }
}

/// Evaluates the target number and the value of `#target = value` without storing anything.
pub fn prepare_assign(
    program: &Program,
    target: ExprId,
    value: ExprId,
    vars: &Variables,
    sys: &dyn SystemVariables,
) -> Result<Assignment, Diagnostic> {
    let node = lookup(program, target)?;
    let span = node.span;
    let target = match &node.expr {
        Expr::Var(index) => Target::Number(eval(program, *index, vars, sys)?.unwrap_or(0.0)),
        Expr::Named(name) => Target::Named(name.clone()),
        _ => {
            let message = "only a variable can be assigned";
            return Err(Diagnostic::error(span, "E-MACRO-VARIABLE", message));
        }
    };
    let value = eval(program, value, vars, sys)?;
    Ok(Assignment {
        target,
        value,
        span,
    })
}

fn lookup(program: &Program, id: ExprId) -> Result<&ExprNode, Diagnostic> {
    program.expr(id).ok_or_else(|| {
        let message = "internal error: the expression is not in this program";
        Diagnostic::error(Span::default(), "E-MACRO-VALUE", message)
    })
}

/// A failure inside one operation, before its span is known: its code and message.
type Fault = (&'static str, String);

fn divide() -> Fault {
    ("E-MACRO-DIVIDE", "division by zero".to_string())
}

/// One unit of work of the explicit-stack evaluation.
#[derive(Debug, Clone, Copy)]
enum Step {
    /// Schedule a node's operands (or push a leaf's value).
    Visit(ExprId),
    /// Combine the node's operands, now on the value stack.
    Apply(ExprId),
}

struct Evaluator<'a> {
    program: &'a Program,
    vars: &'a Variables,
    sys: &'a dyn SystemVariables,
}

impl Evaluator<'_> {
    fn run(&self, root: ExprId) -> Result<Value, Diagnostic> {
        // The common cases (`X12.5` from a macro, `X#24`) need no stacks.
        let node = lookup(self.program, root)?;
        match &node.expr {
            Expr::Num(v) => return Ok(Some(*v)),
            Expr::Var(index) if let Expr::Num(n) = &lookup(self.program, *index)?.expr => {
                return self.variable(*n, node.span);
            }
            _ => {}
        }
        let mut steps = vec![Step::Visit(root)];
        let mut values: Vec<Value> = Vec::new();
        while let Some(step) = steps.pop() {
            match step {
                Step::Visit(id) => {
                    let node = lookup(self.program, id)?;
                    match &node.expr {
                        Expr::Num(v) => values.push(Some(*v)),
                        Expr::Named(name) => values.push(self.named(name, node.span)?),
                        Expr::Call(Func::Exists, arg, _) => {
                            match &lookup(self.program, *arg)?.expr {
                                Expr::Named(name) => {
                                    values.push(Some(flag(self.vars.get_named(name).is_some())));
                                }
                                Expr::Var(index) => {
                                    steps.push(Step::Apply(id));
                                    steps.push(Step::Visit(*index));
                                }
                                _ => {
                                    let m = "`EXISTS` takes a parameter: `EXISTS[#<name>]`";
                                    return Err(Diagnostic::error(node.span, "E-MACRO-VALUE", m));
                                }
                            }
                        }
                        Expr::Var(a) | Expr::Neg(a) | Expr::Call(_, a, None) => {
                            steps.push(Step::Apply(id));
                            steps.push(Step::Visit(*a));
                        }
                        Expr::Binary(_, a, b) | Expr::Call(_, a, Some(b)) => {
                            steps.push(Step::Apply(id));
                            steps.push(Step::Visit(*b));
                            steps.push(Step::Visit(*a));
                        }
                    }
                }
                Step::Apply(id) => {
                    let node = lookup(self.program, id)?;
                    let span = node.span;
                    let value = match &node.expr {
                        Expr::Var(_) => self.variable(num(pop(&mut values, span)?), span)?,
                        Expr::Neg(_) => Some(0.0 - num(pop(&mut values, span)?)),
                        Expr::Binary(op, _, _) => {
                            let b = pop(&mut values, span)?;
                            let a = pop(&mut values, span)?;
                            finite(binary(self.vars.dialect, *op, a, b), span)?
                        }
                        Expr::Call(Func::Exists, _, _) => {
                            let n = pop(&mut values, span)?;
                            Some(flag(self.variable(num(n), span).is_ok()))
                        }
                        Expr::Call(func, _, second) => {
                            let b = second.map(|_| pop(&mut values, span)).transpose()?;
                            let a = pop(&mut values, span)?;
                            finite(call(self.vars.dialect, *func, a, b), span)?
                        }
                        Expr::Num(_) | Expr::Named(_) => return Err(internal(span)),
                    };
                    values.push(value);
                }
            }
        }
        let result = values.pop().ok_or_else(|| internal(node.span))?;
        (values.is_empty().then_some(result)).ok_or_else(|| internal(node.span))
    }

    fn variable(&self, n: f64, span: Span) -> Result<Value, Diagnostic> {
        (self.vars.get(n, self.sys)).map_err(|m| Diagnostic::error(span, "E-MACRO-VARIABLE", m))
    }

    /// Reads `#<name>` as the program does: a name never assigned is an error.
    fn named(&self, name: &str, span: Span) -> Result<Value, Diagnostic> {
        self.vars.get_named(name).map(Some).ok_or_else(|| {
            let name = swarf_syntax::excerpt(&lower(name)).to_string();
            let message = format!("named parameter #<{name}> is not defined");
            Diagnostic::error(span, "E-MACRO-VARIABLE", message)
        })
    }
}

fn pop(values: &mut Vec<Value>, span: Span) -> Result<Value, Diagnostic> {
    values.pop().ok_or_else(|| internal(span))
}

fn internal(span: Span) -> Diagnostic {
    let message = "internal error: malformed expression tree";
    Diagnostic::error(span, "E-MACRO-VALUE", message)
}

/// A vacant operand counts as 0 in arithmetic and functions.
fn num(v: Value) -> f64 {
    v.unwrap_or(0.0)
}

fn flag(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

/// An operation's result as a value; its fault, or an overflow, is an error at `span`.
fn finite(result: Result<f64, Fault>, span: Span) -> Result<Value, Diagnostic> {
    let (code, message) = match result {
        Ok(v) if v.is_finite() => return Ok(Some(v)),
        Ok(_) => ("E-MACRO-VALUE", "the result is too large (overflow)".into()),
        Err(fault) => fault,
    };
    Err(Diagnostic::error(span, code, message))
}

/// A binary operation with the dialect's rules.
fn binary(dialect: Dialect, op: BinOp, a: Value, b: Value) -> Result<f64, Fault> {
    let linuxcnc = is_linuxcnc(dialect);
    let (x, y) = (num(a), num(b));
    Ok(match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div | BinOp::Mod if y == 0.0 => return Err(divide()),
        BinOp::Div => x / y,
        // LinuxCNC: `fmod`, then made non-negative.
        BinOp::Mod if linuxcnc && x % y < 0.0 => x % y + y.abs(),
        BinOp::Mod => x % y,
        BinOp::Pow => power(x, y)?,
        BinOp::And | BinOp::Or | BinOp::Xor if linuxcnc => {
            let (p, q) = (x != 0.0, y != 0.0);
            flag(match op {
                BinOp::And => p && q,
                BinOp::Or => p || q,
                _ => p != q,
            })
        }
        BinOp::And | BinOp::Or | BinOp::Xor => {
            // Fanuc: bit by bit on the values as integers.
            let (p, q) = (bits(x, op)?, bits(y, op)?);
            let r = match op {
                BinOp::And => p & q,
                BinOp::Or => p | q,
                _ => p ^ q,
            };
            r as f64
        }
        BinOp::Eq | BinOp::Ne => {
            let equal = if linuxcnc {
                (x - y).abs() < LINUXCNC_EQUAL
            } else {
                // Fanuc: vacant equals only vacant (`#1 EQ #0` is not `#1 EQ 0`).
                a == b
            };
            flag(equal == (op == BinOp::Eq))
        }
        BinOp::Gt => flag(x > y),
        BinOp::Lt => flag(x < y),
        BinOp::Ge => flag(x >= y || (linuxcnc && (x - y).abs() < LINUXCNC_EQUAL)),
        BinOp::Le => flag(x <= y || (linuxcnc && (x - y).abs() < LINUXCNC_EQUAL)),
    })
}

/// A value as the integer a Fanuc logical operation works on (rounded to the nearest).
fn bits(x: f64, op: BinOp) -> Result<i64, Fault> {
    const LIMIT: f64 = 9_007_199_254_740_992.0; // 2^53
    let r = x.round();
    if r.abs() > LIMIT {
        let op = op.symbol();
        let message = format!("{op} works on integers up to 2^53; {x} is too large");
        return Err(("E-MACRO-VALUE", message));
    }
    Ok(r as i64)
}

/// `a ** b` and `POW[a,b]`.
fn power(x: f64, y: f64) -> Result<f64, Fault> {
    if x < 0.0 && y.fract() != 0.0 {
        let message =
            format!("a negative number ({x}) cannot be raised to a fractional power ({y})");
        return Err(("E-MACRO-DOMAIN", message));
    }
    if x == 0.0 && y < 0.0 {
        return Err(divide());
    }
    Ok(x.powf(y))
}

/// Sine of `deg` degrees, exact at multiples of 90° (`COS[90]` is 0, not 6e-17).
fn sin_deg(deg: f64) -> f64 {
    match deg.rem_euclid(360.0) {
        0.0 | 180.0 => 0.0,
        90.0 => 1.0,
        270.0 => -1.0,
        r => r.to_radians().sin(),
    }
}

fn cos_deg(deg: f64) -> f64 {
    sin_deg(deg.rem_euclid(360.0) + 90.0)
}

/// An angle in 0°–360° (Fanuc parameter NAT = 0, the default).
fn full_turn(deg: f64) -> f64 {
    // `+ 0.0` turns -0 into 0.
    if deg < 0.0 { deg + 360.0 } else { deg + 0.0 }
}

/// A function call with the dialect's rules.
fn call(dialect: Dialect, func: Func, a: Value, b: Option<Value>) -> Result<f64, Fault> {
    let linuxcnc = is_linuxcnc(dialect);
    let x = num(a);
    let outside_domain = match func {
        Func::Tan if cos_deg(x) == 0.0 => Some(format!("TAN[{x}] is infinite")),
        Func::Asin | Func::Acos if !(-1.0..=1.0).contains(&x) => Some(format!(
            "{}[{x}] is undefined: the argument must be between -1 and 1",
            func.name()
        )),
        Func::Sqrt if x < 0.0 => Some(format!("SQRT of a negative number ({x})")),
        Func::Ln if x <= 0.0 => Some(format!("LN of zero or a negative number ({x})")),
        _ => None,
    };
    if let Some(message) = outside_domain {
        return Err(("E-MACRO-DOMAIN", message));
    }
    Ok(match func {
        Func::Sin => sin_deg(x),
        Func::Cos => cos_deg(x),
        Func::Tan => sin_deg(x) / cos_deg(x),
        Func::Acos => x.acos().to_degrees(),
        Func::Asin if linuxcnc => x.asin().to_degrees(),
        // Fanuc (NAT = 0): 270°–90°.
        Func::Asin => full_turn(x.asin().to_degrees()),
        Func::Atan => {
            let deg = b.map_or(x.atan(), |b| x.atan2(num(b))).to_degrees();
            if linuxcnc { deg } else { full_turn(deg) }
        }
        Func::Sqrt => x.sqrt(),
        Func::Abs => x.abs(),
        // Half away from zero, in every dialect.
        Func::Round => x.round(),
        Func::Fix if linuxcnc => x.floor(),
        Func::Fix => x.trunc(),
        Func::Fup if linuxcnc => x.ceil(),
        // Fanuc: away from zero (FUP[-1.2] = -2).
        Func::Fup => {
            let t = x.trunc();
            if t == x { t } else { t + x.signum() }
        }
        Func::Ln => x.ln(),
        Func::Exp => x.exp(),
        Func::Pow => power(x, num(b.flatten()))?,
        Func::Bin => bin(x)?,
        Func::Bcd => bcd(x)?,
        // Handled by the evaluator (it needs the variable store).
        Func::Exists => 0.0,
    })
}

/// A non-negative whole number for BIN/BCD.
fn whole(x: f64, func: &str, max: f64) -> Result<u64, Fault> {
    let r = x.round();
    if (x - r).abs() > 1e-6 || r < 0.0 || r > max {
        let message = format!("{func} needs a whole number from 0 to {max}, not {x}");
        return Err(("E-MACRO-VALUE", message));
    }
    Ok(r as u64)
}

/// BCD → binary: each 4-bit group is one decimal digit.
fn bin(x: f64) -> Result<f64, Fault> {
    let mut v = whole(x, "BIN", f64::from(u32::MAX))?;
    let (mut out, mut scale) = (0u64, 1u64);
    while v > 0 {
        let digit = v & 0xF;
        if digit > 9 {
            let message = format!("BIN[{x}] is not a BCD value (a 4-bit group is over 9)");
            return Err(("E-MACRO-VALUE", message));
        }
        out += digit * scale;
        scale *= 10;
        v >>= 4;
    }
    Ok(out as f64)
}

/// Binary → BCD: each decimal digit in 4 bits (up to 8 digits, a 32-bit signal).
fn bcd(x: f64) -> Result<f64, Fault> {
    let mut v = whole(x, "BCD", 99_999_999.0)?;
    let (mut out, mut shift) = (0u64, 0u32);
    while v > 0 {
        out |= (v % 10) << shift;
        shift += 4;
        v /= 10;
    }
    Ok(out as f64)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use swarf_syntax::{Statement, parse};

    fn eval_condition(
        program: &Program,
        id: ExprId,
        vars: &Variables,
        sys: &dyn SystemVariables,
    ) -> Result<bool, Diagnostic> {
        Ok(eval(program, id, vars, sys)?.is_some_and(|v| v != 0.0))
    }

    fn assign(
        program: &Program,
        target: ExprId,
        value: ExprId,
        vars: &mut Variables,
        sys: &mut dyn SystemVariables,
    ) -> Result<(), Diagnostic> {
        prepare_assign(program, target, value, vars, sys)?.apply(vars, sys)
    }

    /// System variables for tests: #1000–#1015 inputs (read-only), #2001 tool offset
    /// (writable), #3000 alarm (write-only: refuses), #4001 modal G group 1, #5221 G54 X; and
    /// LinuxCNC's `#<_metric>`.
    #[derive(Default)]
    struct TestSys {
        values: HashMap<u32, Value>,
    }

    impl TestSys {
        fn new() -> Self {
            let mut values = HashMap::new();
            values.insert(1000, Some(1.0));
            values.insert(2001, Some(0.25));
            values.insert(4001, Some(1.0));
            values.insert(5221, Some(-100.0));
            values.insert(3000, None);
            TestSys { values }
        }
    }

    impl SystemVariables for TestSys {
        fn read(&self, n: u32) -> Option<Value> {
            self.values.get(&n).copied()
        }

        fn write(&mut self, n: u32, v: Value) -> Result<bool, String> {
            match n {
                1000..=1015 | 4001 => Err(format!("#{n} is read-only")),
                3000 => Err(format!("alarm {}", v.unwrap_or(0.0))),
                2001 | 5221 => {
                    self.values.insert(n, v);
                    Ok(true)
                }
                _ => Ok(false),
            }
        }
    }

    /// Runs every assignment (also those after `IF … THEN`) of `text` in order; the first error
    /// stops the run and is returned with the text its span covers.
    fn exec(
        text: &str,
        dialect: Dialect,
        vars: &mut Variables,
        sys: &mut TestSys,
    ) -> Result<(), (Diagnostic, String)> {
        let program = parse(text, dialect);
        assert!(
            program.diagnostics.is_empty(),
            "{text}: {:?}",
            program.diagnostics
        );
        for block in &program.blocks {
            for statement in block.statements() {
                let r = match statement {
                    Statement::Assign { target, value } => {
                        assign(&program, *target, *value, vars, sys)
                    }
                    Statement::If { cond, then } => {
                        match eval_condition(&program, *cond, vars, sys) {
                            Ok(true) => match then.as_ref() {
                                Statement::Assign { target, value } => {
                                    assign(&program, *target, *value, vars, sys)
                                }
                                _ => Ok(()),
                            },
                            Ok(false) => Ok(()),
                            Err(e) => Err(e),
                        }
                    }
                    _ => Ok(()),
                };
                r.map_err(|e| {
                    let shown = text[e.span.range()].to_string();
                    (e, shown)
                })?;
            }
        }
        Ok(())
    }

    /// Runs `text` on a fresh store and returns it.
    fn run(text: &str, dialect: Dialect) -> Variables {
        let mut vars = Variables::new(dialect);
        exec(text, dialect, &mut vars, &mut TestSys::new()).unwrap();
        vars
    }

    /// The value of `expr` (assigned to #1 in the Fanuc family, #31 in LinuxCNC).
    fn value(expr: &str, dialect: Dialect) -> Value {
        let text = if dialect == Dialect::LinuxCnc {
            format!("#31 = [{expr}]")
        } else {
            format!("#1 = {expr}")
        };
        let vars = run(&text, dialect);
        vars.get(
            if dialect == Dialect::LinuxCnc {
                31.0
            } else {
                1.0
            },
            &TestSys::new(),
        )
        .unwrap()
    }

    fn fanuc(expr: &str) -> f64 {
        value(expr, Dialect::Fanuc).unwrap()
    }

    fn lcnc(expr: &str) -> f64 {
        value(expr, Dialect::LinuxCnc).unwrap()
    }

    /// The error of running `text` on a fresh store: its code, message and the text it covers.
    fn error(text: &str, dialect: Dialect) -> (&'static str, String, String) {
        let mut vars = Variables::new(dialect);
        let (e, shown) = exec(text, dialect, &mut vars, &mut TestSys::new()).unwrap_err();
        (e.code, e.message, shown)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn the_store_grows_as_variables_are_set() {
        let sys = TestSys::new();
        // Unset variables read as the dialect's initial value, at either end of the store.
        let lcnc = Variables::new(Dialect::LinuxCnc);
        assert_eq!(lcnc.get(31.0, &sys), Ok(Some(0.0)));
        assert_eq!(lcnc.get(5601.0, &sys), Ok(Some(0.0)));
        assert!(lcnc.get(5602.0, &sys).is_err());
        let fanuc = Variables::new(Dialect::Fanuc);
        assert_eq!(fanuc.get(100.0, &sys), Ok(None));
        assert_eq!(fanuc.get(999.0, &sys), Ok(None));
        // A set variable reads back; those below it that were not set keep the initial value.
        let vars = run("#4000 = 7\n", Dialect::LinuxCnc);
        assert_eq!(vars.get(4000.0, &sys), Ok(Some(7.0)));
        assert_eq!(vars.get(3999.0, &sys), Ok(Some(0.0)));
        assert_eq!(vars.get(4001.0, &sys), Ok(Some(1.0)), "a system variable");
        assert_eq!(vars.get(4002.0, &sys), Ok(Some(0.0)));
        let vars = run("#998 = 2.5\n", Dialect::Fanuc);
        assert_eq!(vars.get(998.0, &sys), Ok(Some(2.5)));
        assert_eq!(vars.get(500.0, &sys), Ok(None));
        // A variable set back to its initial value reads as in a store that never grew.
        let zero = run("#4000 = 0\n", Dialect::LinuxCnc);
        assert_eq!(zero.get(4000.0, &sys), lcnc.get(4000.0, &sys));
        let mut vacated = run("#998 = 2.5\n", Dialect::Fanuc);
        vacated.set(998.0, None, &mut TestSys::new()).unwrap();
        assert_eq!(vacated.get(998.0, &sys), fanuc.get(998.0, &sys));
    }

    #[test]
    fn arithmetic_precedence() {
        assert_eq!(fanuc("1 + 2 * 3"), 7.0);
        assert_eq!(fanuc("[1 + 2] * 3"), 9.0);
        assert_eq!(fanuc("10 - 4 - 3"), 3.0);
        assert_eq!(fanuc("24 / 4 / 2"), 3.0);
        assert_eq!(fanuc("-2 * 3"), -6.0);
        assert_eq!(fanuc("1 + 2 EQ 3"), 1.0);
        assert_eq!(lcnc("2 ** 3 ** 2"), 512.0);
        assert_eq!(lcnc("1 + 2 ** 3 * 2"), 17.0);
    }

    #[test]
    fn logical_precedence_per_dialect() {
        // Fanuc: AND binds like `*`, OR/XOR like `+`.
        assert_eq!(fanuc("2 + 3 AND 1"), 3.0);
        assert_eq!(fanuc("5 OR 2 AND 3"), 7.0);
        // LinuxCNC: logical operators bind loosest and give 1 or 0.
        assert_eq!(lcnc("2 + 3 and 1"), 1.0);
        assert_eq!(lcnc("1 eq 1 and 2 gt 3"), 0.0);
        assert_eq!(lcnc("1 eq 1 or 2 gt 3"), 1.0);
    }

    #[test]
    fn fanuc_logic_is_bitwise_linuxcnc_logic_is_boolean() {
        assert_eq!(fanuc("12 AND 10"), 8.0);
        assert_eq!(fanuc("12 OR 10"), 14.0);
        assert_eq!(fanuc("12 XOR 10"), 6.0);
        assert_eq!(lcnc("12 and 10"), 1.0);
        assert_eq!(lcnc("12 or 0"), 1.0);
        assert_eq!(lcnc("12 xor 10"), 0.0);
        assert_eq!(lcnc("0 xor 10"), 1.0);
        assert_eq!(lcnc("0 and 10"), 0.0);
    }

    #[test]
    fn comparisons_give_one_or_zero() {
        for (expr, want) in [
            ("2 GT 1", 1.0),
            ("1 GT 1", 0.0),
            ("1 GE 1", 1.0),
            ("1 LT 2", 1.0),
            ("2 LE 1", 0.0),
            ("3 NE 3", 0.0),
            ("3 EQ 3", 1.0),
        ] {
            assert_eq!(fanuc(expr), want, "{expr}");
            assert_eq!(lcnc(expr), want, "{expr}");
        }
        // LinuxCNC compares with a tolerance of 1e-6; Fanuc exactly.
        assert_eq!(lcnc("1 eq 1.0000001"), 1.0);
        assert_eq!(lcnc("1 ne 1.0000001"), 0.0);
        assert_eq!(lcnc("1.0000001 le 1"), 1.0);
        assert_eq!(fanuc("1 EQ 1.0000001"), 0.0);
        assert_eq!(fanuc("1.0000001 LE 1"), 0.0);
    }

    #[test]
    fn vacant_rules() {
        let vars = run(
            "#1 = #0 + 1\n#2 = #0\n#3 = #0 * 5\n#4 = -#0\n#6 = #5\n\
             #10 = #5 EQ #0\n#11 = 0 EQ #0\n#12 = #5 NE 0\n#13 = #5 GE #0\n\
             #14 = #5 GT 0\n#15 = #5 LT 1\n#16 = #5 EQ 0\n#17 = ABS[#0]\n#18 = [#0 + 0] EQ #0",
            Dialect::Fanuc,
        );
        let sys = TestSys::new();
        let get = |n: f64| vars.get(n, &sys).unwrap();
        assert_eq!(get(1.0), Some(1.0));
        assert_eq!(get(2.0), None, "`#2 = #0` keeps #2 vacant");
        assert_eq!(get(3.0), Some(0.0));
        assert_eq!(get(4.0), Some(0.0));
        assert_eq!(get(6.0), None);
        assert_eq!(get(10.0), Some(1.0), "vacant EQ #0");
        assert_eq!(get(11.0), Some(0.0), "0 EQ #0");
        assert_eq!(get(12.0), Some(1.0), "vacant NE 0");
        assert_eq!(get(13.0), Some(1.0), "vacant GE #0");
        assert_eq!(get(14.0), Some(0.0), "vacant GT 0");
        assert_eq!(get(15.0), Some(1.0), "vacant LT 1 (as 0)");
        assert_eq!(get(16.0), Some(0.0), "vacant EQ 0");
        assert_eq!(get(17.0), Some(0.0));
        assert_eq!(get(18.0), Some(0.0), "a sum is 0, not vacant");
        assert_eq!(get(0.0), None);
    }

    #[test]
    fn conditions_vacant_is_false() {
        let text = "IF [#1] THEN #2 = 1\nIF [#0 EQ #0] THEN #3 = 1\nIF [0] THEN #4 = 1\n\
                    IF [0.5] THEN #5 = 1";
        let vars = run(text, Dialect::Fanuc);
        let sys = TestSys::new();
        assert_eq!(vars.get(2.0, &sys).unwrap(), None);
        assert_eq!(vars.get(3.0, &sys).unwrap(), Some(1.0));
        assert_eq!(vars.get(4.0, &sys).unwrap(), None);
        assert_eq!(vars.get(5.0, &sys).unwrap(), Some(1.0));
    }

    #[test]
    fn fix_fup_per_dialect() {
        assert_eq!(fanuc("FIX[-1.2]"), -1.0);
        assert_eq!(fanuc("FUP[-1.2]"), -2.0);
        assert_eq!(fanuc("FIX[1.7]"), 1.0);
        assert_eq!(fanuc("FUP[1.2]"), 2.0);
        assert_eq!(fanuc("FUP[3]"), 3.0);
        assert_eq!(fanuc("FUP[-3]"), -3.0);
        assert_eq!(lcnc("fix[-1.2]"), -2.0);
        assert_eq!(lcnc("fup[-1.2]"), -1.0);
        assert_eq!(lcnc("fix[1.7]"), 1.0);
        assert_eq!(lcnc("fup[1.2]"), 2.0);
    }

    #[test]
    fn round_is_half_away_from_zero() {
        assert_eq!(fanuc("ROUND[2.5]"), 3.0);
        assert_eq!(fanuc("ROUND[-2.5]"), -3.0);
        assert_eq!(fanuc("ROUND[2.4]"), 2.0);
        assert_eq!(lcnc("round[-2.5]"), -3.0);
        assert_eq!(lcnc("round[0.5]"), 1.0);
    }

    #[test]
    fn atan_and_asin_ranges_per_dialect() {
        assert_eq!(fanuc("ATAN[1]/[1]"), 45.0);
        assert_eq!(fanuc("ATAN[1,1]"), 45.0);
        assert_eq!(fanuc("ATAN[-1]/[-1]"), 225.0);
        assert_eq!(fanuc("ATAN[-1]/[1]"), 315.0);
        assert_eq!(fanuc("ATAN[0]/[-1]"), 180.0);
        assert_eq!(lcnc("atan[-1]/[-1]"), -135.0);
        assert_eq!(lcnc("atan[-1]/[1]"), -45.0);
        assert_eq!(lcnc("atan[1]/[-1]"), 135.0);
        assert!(close(fanuc("ATAN[1]"), 45.0));
        assert_eq!(fanuc("ASIN[1]"), 90.0);
        assert!(close(fanuc("ASIN[-0.5]"), 330.0));
        assert!(close(lcnc("asin[-0.5]"), -30.0));
        assert_eq!(fanuc("ACOS[-1]"), 180.0);
        assert_eq!(fanuc("ACOS[1]"), 0.0);
    }

    #[test]
    fn mod_per_dialect() {
        assert_eq!(fanuc("-7 MOD 3"), -1.0);
        assert_eq!(fanuc("7 MOD 3"), 1.0);
        assert_eq!(fanuc("7 MOD -3"), 1.0);
        assert_eq!(fanuc("7.5 MOD 2"), 1.5);
        assert_eq!(lcnc("-7 mod 3"), 2.0);
        assert_eq!(lcnc("7 mod -3"), 1.0);
        assert_eq!(lcnc("-7 mod -3"), 2.0);
        assert_eq!(lcnc("7 mod 3"), 1.0);
    }

    #[test]
    fn trigonometry_in_degrees() {
        assert!(close(fanuc("SIN[30]"), 0.5));
        assert_eq!(fanuc("COS[90]"), 0.0);
        assert_eq!(fanuc("SIN[180]"), 0.0);
        assert_eq!(fanuc("SIN[-90]"), -1.0);
        assert_eq!(fanuc("COS[360]"), 1.0);
        assert_eq!(fanuc("COS[180]"), -1.0);
        assert!(close(fanuc("COS[60]"), 0.5));
        assert!(close(fanuc("TAN[45]"), 1.0));
        assert!(close(lcnc("sin[30]"), 0.5));
        assert_eq!(lcnc("cos[90]"), 0.0);
    }

    #[test]
    fn other_functions() {
        assert_eq!(fanuc("SQRT[16]"), 4.0);
        assert_eq!(fanuc("SQR[9]"), 3.0);
        assert_eq!(fanuc("ABS[-3.5]"), 3.5);
        assert_eq!(fanuc("LN[1]"), 0.0);
        assert_eq!(fanuc("EXP[0]"), 1.0);
        assert!(close(fanuc("LN[EXP[2]]"), 2.0));
        assert_eq!(fanuc("POW[2,10]"), 1024.0);
        assert_eq!(fanuc("POW[-2,3]"), -8.0);
        assert_eq!(fanuc("BCD[25]"), 37.0);
        assert_eq!(fanuc("BIN[37]"), 25.0);
        assert_eq!(fanuc("BIN[BCD[12345678]]"), 12_345_678.0);
        assert_eq!(fanuc("BCD[0]"), 0.0);
        assert_eq!(lcnc("sqrt[2] * sqrt[2] gt 1.999"), 1.0);
    }

    #[test]
    fn assignment_keeps_full_precision() {
        assert_eq!(fanuc("1 / 3"), 1.0 / 3.0);
        assert_eq!(fanuc("0.1 + 0.2"), 0.1 + 0.2);
    }

    #[test]
    fn errors_carry_the_node_span() {
        let (code, message, shown) = error("#1 = 2 + 1 / [#2 - #2]", Dialect::Fanuc);
        assert_eq!(code, "E-MACRO-DIVIDE");
        assert_eq!(message, "division by zero");
        assert_eq!(shown, "1 / [#2 - #2]");

        let (code, _, shown) = error("#1 = 5 MOD 0", Dialect::Fanuc);
        assert_eq!((code, shown.as_str()), ("E-MACRO-DIVIDE", "5 MOD 0"));

        for (text, shown) in [
            ("#1 = 1 + SQRT[-4]", "SQRT[-4]"),
            ("#1 = ASIN[2]", "ASIN[2]"),
            ("#1 = ACOS[-1.5]", "ACOS[-1.5]"),
            ("#1 = LN[0]", "LN[0]"),
            ("#1 = LN[-1]", "LN[-1]"),
            ("#1 = TAN[90]", "TAN[90]"),
            ("#1 = POW[-8, 0.5]", "POW[-8, 0.5]"),
        ] {
            let (code, _, got) = error(text, Dialect::Fanuc);
            assert_eq!((code, got.as_str()), ("E-MACRO-DOMAIN", shown), "{text}");
        }
        let (code, _, shown) = error("#31 = [-8 ** 0.5]", Dialect::LinuxCnc);
        assert_eq!((code, shown.as_str()), ("E-MACRO-DOMAIN", "-8 ** 0.5"));

        for (text, shown) in [
            ("#1 = BIN[10]", "BIN[10]"),
            ("#1 = BCD[-1]", "BCD[-1]"),
            ("#1 = BCD[1.5]", "BCD[1.5]"),
            ("#1 = EXP[1000]", "EXP[1000]"),
        ] {
            let (code, _, got) = error(text, Dialect::Fanuc);
            assert_eq!((code, got.as_str()), ("E-MACRO-VALUE", shown), "{text}");
        }
    }

    #[test]
    fn variable_errors() {
        let (code, message, shown) = error("#1 = 2 * #50", Dialect::Fanuc);
        assert_eq!(code, "E-MACRO-VARIABLE");
        assert_eq!(message, "variable #50 does not exist on Fanuc 0i-M");
        assert_eq!(shown, "#50");

        let (_, message, shown) = error("#250 = 1", Dialect::Syntec);
        assert_eq!(message, "variable #250 does not exist on Syntec 900M");
        assert_eq!(shown, "#250");

        let (code, message, shown) = error("#1 = #[1.5]", Dialect::Fanuc);
        assert_eq!(code, "E-MACRO-VARIABLE");
        assert!(message.contains("whole number"), "{message}");
        assert_eq!(shown, "#[1.5]");

        let (_, message, _) = error("#1 = #[0 - 1]", Dialect::Fanuc);
        assert!(message.contains("negative"), "{message}");

        let (code, message, shown) = error("#0 = 1", Dialect::Fanuc);
        assert_eq!(code, "E-MACRO-VARIABLE");
        assert!(message.contains("#0"), "{message}");
        assert_eq!(shown, "#0");

        // A system variable the machine does not know.
        let (_, message, shown) = error("#1 = #1234", Dialect::Fanuc);
        assert_eq!(message, "variable #1234 does not exist on Fanuc 0i-M");
        assert_eq!(shown, "#1234");

        // Within 1e-6 of a whole number is that number.
        let vars = run("#[2.0000000001] = 4\n#3 = #[1 + 1]", Dialect::Fanuc);
        assert_eq!(vars.get(3.0, &TestSys::new()).unwrap(), Some(4.0));

        // `##n`: the number comes from a variable.
        let vars = run("#1 = 100\n##1 = 7\n#2 = ##1", Dialect::Fanuc);
        assert_eq!(vars.get(100.0, &TestSys::new()).unwrap(), Some(7.0));
        assert_eq!(vars.get(2.0, &TestSys::new()).unwrap(), Some(7.0));
    }

    #[test]
    fn fanuc_ranges() {
        let vars = run(
            "#33 = 1\n#100 = 2\n#199 = 3\n#500 = 4\n#999 = 5",
            Dialect::Fanuc,
        );
        let sys = TestSys::new();
        for (n, want) in [
            (33.0, 1.0),
            (100.0, 2.0),
            (199.0, 3.0),
            (500.0, 4.0),
            (999.0, 5.0),
        ] {
            assert_eq!(vars.get(n, &sys).unwrap(), Some(want), "#{n}");
        }
        for n in [34.0, 99.0, 200.0, 499.0, 1001.0] {
            assert!(vars.get(n, &sys).is_err(), "#{n}");
        }
        assert!(vars.get(500.0, &sys).is_ok());
        assert!(vars.get(300.0, &sys).is_err());
    }

    #[test]
    fn argument_specification_one() {
        let expected = [
            (b'A', 1),
            (b'B', 2),
            (b'C', 3),
            (b'I', 4),
            (b'J', 5),
            (b'K', 6),
            (b'D', 7),
            (b'E', 8),
            (b'F', 9),
            (b'H', 11),
            (b'M', 13),
            (b'Q', 17),
            (b'R', 18),
            (b'S', 19),
            (b'T', 20),
            (b'U', 21),
            (b'V', 22),
            (b'W', 23),
            (b'X', 24),
            (b'Y', 25),
            (b'Z', 26),
        ];
        for (letter, n) in expected {
            assert_eq!(argument_variable(letter), Some(n), "{}", char::from(letter));
        }
        for letter in *b"GLNOP" {
            assert_eq!(argument_variable(letter), None, "{}", char::from(letter));
        }
        assert_eq!(argument_variable(b'x'), Some(24));
    }

    #[test]
    fn frames_keep_locals_per_level_and_share_commons() {
        let mut sys = TestSys::new();
        let mut vars = Variables::new(Dialect::Fanuc);
        exec(
            "#1 = 5\n#100 = 7\n#500 = 9",
            Dialect::Fanuc,
            &mut vars,
            &mut sys,
        )
        .unwrap();

        vars.push_frame(&[(1, 2.0), (24, 10.0), (40, 1.0)]);
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(2.0));
        assert_eq!(vars.get(24.0, &sys).unwrap(), Some(10.0));
        assert_eq!(vars.get(2.0, &sys).unwrap(), None, "locals start vacant");
        assert_eq!(vars.get(100.0, &sys).unwrap(), Some(7.0));
        exec(
            "#1 = #1 + 1\n#100 = 8\n#2 = 3",
            Dialect::Fanuc,
            &mut vars,
            &mut sys,
        )
        .unwrap();

        vars.push_frame(&[]);
        assert_eq!(vars.get(1.0, &sys).unwrap(), None);
        vars.pop_frame();

        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(3.0));
        assert_eq!(vars.get(2.0, &sys).unwrap(), Some(3.0));
        vars.pop_frame();
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(5.0));
        assert_eq!(vars.get(2.0, &sys).unwrap(), None);
        assert_eq!(vars.get(100.0, &sys).unwrap(), Some(8.0));
        vars.pop_frame();
        assert_eq!(
            vars.get(1.0, &sys).unwrap(),
            Some(5.0),
            "the main level is never left"
        );
    }

    #[test]
    fn system_variables_are_delegated() {
        let mut sys = TestSys::new();
        let mut vars = Variables::new(Dialect::Fanuc);
        exec(
            "#1 = #4001\n#2 = #1000 + #2001\n#2001 = 0.5\n#3 = #2001\n#4 = #3000",
            Dialect::Fanuc,
            &mut vars,
            &mut sys,
        )
        .unwrap();
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(1.0));
        assert_eq!(vars.get(2.0, &sys).unwrap(), Some(1.25));
        assert_eq!(vars.get(3.0, &sys).unwrap(), Some(0.5));
        assert_eq!(
            vars.get(4.0, &sys).unwrap(),
            None,
            "a vacant system variable"
        );
        assert_eq!(sys.values.get(&2001), Some(&Some(0.5)));

        let err = exec("#3000 = 12", Dialect::Fanuc, &mut vars, &mut sys).unwrap_err();
        assert_eq!(err.0.code, "E-MACRO-VARIABLE");
        assert_eq!(err.0.message, "alarm 12");
        assert_eq!(err.1, "#3000");
        let err = exec("#1000 = 1", Dialect::Fanuc, &mut vars, &mut sys).unwrap_err();
        assert_eq!(err.0.message, "#1000 is read-only");
        let err = exec("#1 = #[1000 + 16]", Dialect::Fanuc, &mut vars, &mut sys).unwrap_err();
        assert_eq!(err.0.message, "variable #1016 does not exist on Fanuc 0i-M");
        assert_eq!(err.1, "#[1000 + 16]");

        // LinuxCNC: the machine's parameters come first, inside the numbered range too.
        let mut vars = Variables::new(Dialect::LinuxCnc);
        exec(
            "#31 = #5221\n#5221 = 12\n#32 = #5221",
            Dialect::LinuxCnc,
            &mut vars,
            &mut sys,
        )
        .unwrap();
        assert_eq!(vars.get(31.0, &sys).unwrap(), Some(-100.0));
        assert_eq!(vars.get(32.0, &sys).unwrap(), Some(12.0));
    }

    #[test]
    fn linuxcnc_numbered_parameters() {
        let mut sys = TestSys::new();
        let mut vars = Variables::new(Dialect::LinuxCnc);
        exec(
            "#1 = [#200 + 1]\n#2 = #200\n#31 = 4\n#5601 = 2",
            Dialect::LinuxCnc,
            &mut vars,
            &mut sys,
        )
        .unwrap();
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(1.0));
        assert_eq!(
            vars.get(2.0, &sys).unwrap(),
            Some(0.0),
            "parameters default to 0"
        );
        assert_eq!(vars.get(5601.0, &sys).unwrap(), Some(2.0));

        // #1–#30 are local to an o-word call, #31 and up global.
        vars.push_frame(&[(1, 10.0), (2, 20.0)]);
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(10.0));
        assert_eq!(vars.get(3.0, &sys).unwrap(), Some(0.0));
        assert_eq!(vars.get(31.0, &sys).unwrap(), Some(4.0));
        exec("#1 = 99\n#31 = 5", Dialect::LinuxCnc, &mut vars, &mut sys).unwrap();
        vars.pop_frame();
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(1.0));
        assert_eq!(vars.get(31.0, &sys).unwrap(), Some(5.0));

        let (code, message, shown) = error("#1 = #6000", Dialect::LinuxCnc);
        assert_eq!(code, "E-MACRO-VARIABLE");
        assert_eq!(message, "variable #6000 does not exist on LinuxCNC");
        assert_eq!(shown, "#6000");
        let (_, message, _) = error("#1 = #0", Dialect::LinuxCnc);
        assert_eq!(message, "variable #0 does not exist on LinuxCNC");
        // LinuxCNC accepts a number within 1e-4 of a whole one.
        let vars = run("#[2.00001] = 3", Dialect::LinuxCnc);
        assert_eq!(vars.get(2.0, &sys).unwrap(), Some(3.0));
    }

    #[test]
    fn linuxcnc_named_parameters() {
        let mut sys = TestSys::new();
        let mut vars = Variables::new(Dialect::LinuxCnc);
        exec(
            "#<Depth> = 2\n#<_Safe> = 5\n#1 = [#<depth> + #<_safe>]\n\
             #3 = EXISTS[#<depth>]\n#4 = EXISTS[#<nothing>]\n\
             #6 = EXISTS[#31]\n#7 = EXISTS[#6000]",
            Dialect::LinuxCnc,
            &mut vars,
            &mut sys,
        )
        .unwrap();
        let get = |vars: &Variables, n: f64| vars.get(n, &TestSys::new()).unwrap();
        assert_eq!(get(&vars, 1.0), Some(7.0));
        assert_eq!(get(&vars, 3.0), Some(1.0));
        assert_eq!(get(&vars, 4.0), Some(0.0));
        assert_eq!(get(&vars, 6.0), Some(1.0));
        assert_eq!(get(&vars, 7.0), Some(0.0));
        assert_eq!(vars.get_named("depth"), Some(2.0));
        assert_eq!(vars.get_named("_SAFE"), Some(5.0));

        // A call level sees the globals but not the caller's locals.
        vars.push_frame(&[]);
        let err = exec("#1 = #<depth>", Dialect::LinuxCnc, &mut vars, &mut sys).unwrap_err();
        assert_eq!(err.0.code, "E-MACRO-VARIABLE");
        assert_eq!(err.0.message, "named parameter #<depth> is not defined");
        assert_eq!(err.1, "#<depth>");
        exec(
            "#<depth> = 8\n#<_safe> = 6\n#1 = [#<depth> + #<_safe>]",
            Dialect::LinuxCnc,
            &mut vars,
            &mut sys,
        )
        .unwrap();
        assert_eq!(get(&vars, 1.0), Some(14.0));
        vars.pop_frame();
        assert_eq!(vars.get_named("depth"), Some(2.0));
        assert_eq!(vars.get_named("_safe"), Some(6.0));

        vars.set_named("_value", Some(3.0));
        assert_eq!(vars.get_named("_value"), Some(3.0));
        vars.set_named("_value", None);
        assert_eq!(vars.get_named("_value"), None);
    }

    #[test]
    fn prepared_assignments_see_the_old_values() {
        let text = "#1 = 1\n#1 = 5 #2 = [#1 + 1]";
        let program = parse(text, Dialect::LinuxCnc);
        assert!(program.diagnostics.is_empty(), "{:?}", program.diagnostics);
        let mut sys = TestSys::new();
        let mut vars = Variables::new(Dialect::LinuxCnc);
        for block in &program.blocks {
            let prepared: Vec<Assignment> = block
                .statements()
                .iter()
                .filter_map(|s| match s {
                    Statement::Assign { target, value } => {
                        Some(prepare_assign(&program, *target, *value, &vars, &sys).unwrap())
                    }
                    _ => None,
                })
                .collect();
            for a in &prepared {
                a.apply(&mut vars, &mut sys).unwrap();
            }
        }
        assert_eq!(vars.get(1.0, &sys).unwrap(), Some(5.0));
        assert_eq!(vars.get(2.0, &sys).unwrap(), Some(2.0));
    }

    #[test]
    fn long_chains_do_not_overflow_the_stack() {
        let terms = 200_000;
        let mut text = String::from("#1 = 1");
        for _ in 1..terms {
            text.push_str("+1");
        }
        assert_eq!(fanuc(&text[5..]), f64::from(terms));
    }

    #[test]
    fn errors_become_diagnostics() {
        let program = parse("#1 = 1 / 0", Dialect::Fanuc);
        let mut sys = TestSys::default();
        let mut vars = Variables::new(Dialect::Fanuc);
        let assigned = program.blocks[0].statements().iter().any(|s| {
            matches!(s, Statement::Assign { target, value }
                if assign(&program, *target, *value, &mut vars, &mut sys).is_err())
        });
        assert!(assigned, "the division by zero is reported");
    }
}
