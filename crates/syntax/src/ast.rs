//! The parsed program: blocks of address words and macro statements, with byte spans back into
//! the text. Expressions live in one arena per program ([`Program::exprs`]) so that a word stays
//! small and `Copy` and a million-line program is not a million boxes.

use std::num::NonZeroU32;

use smallvec::SmallVec;

use crate::{Diagnostic, Dialect, LineIndex, Span};

/// How a word was written besides its letter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WordForm {
    /// `X12.5`.
    #[default]
    Plain,
    /// A comma word: `,C2.` chamfer, `,R5.` corner rounding (`,A` angle).
    Comma,
    /// An indexed word `F2=1000` (retract feed) or `S1=150` (spindle 1): the index.
    Indexed(u8),
}

/// One address word such as `X-12.5`, `,R5.`, `F2=800` or `X#1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// The address letter, uppercase ASCII.
    pub letter: u8,
    /// The value as written (0 when the value is an expression: see `expr`).
    pub value: f64,
    /// Whether the value was written with a decimal point (controls read the two differently).
    pub has_point: bool,
    /// The whole word, letter included.
    pub span: Span,
    /// Comma or indexed form.
    pub form: WordForm,
    /// The expression giving the value (`X#1`, `G#30`, `Z-[#2+1]`), evaluated when the block runs.
    pub expr: Option<ExprId>,
}

impl Word {
    /// The address letter as a `char`.
    pub fn letter(&self) -> char {
        char::from(self.letter)
    }
}

/// Index of an expression node in [`Program::exprs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ExprId(NonZeroU32);

impl ExprId {
    /// The node's position in [`Program::exprs`].
    pub fn index(self) -> usize {
        self.0.get() as usize - 1
    }

    pub(crate) fn from_index(index: usize) -> Option<ExprId> {
        let number = u32::try_from(index + 1).ok()?;
        NonZeroU32::new(number).map(ExprId)
    }
}

/// Declares an enum from one row a variant (the variant, its name, its documentation), with
/// `ALL` (every variant, in order), the function that names each, and `Display` by that name.
macro_rules! named_enum {
    (
        $(#[$meta:meta])* pub enum $enum:ident;
        $(#[$fn_meta:meta])* fn $fn:ident;
        $($(#[$attr:meta])* $variant:ident $name:literal $doc:literal;)*
    ) => {
        $(#[$meta])*
        pub enum $enum {
            $(#[doc = $doc] $(#[$attr])* $variant,)*
        }

        impl $enum {
            /// Every variant, in order.
            pub const ALL: [$enum; [$($name),*].len()] = [$($enum::$variant),*];

            $(#[$fn_meta])*
            pub fn $fn(self) -> &'static str {
                match self {
                    $($enum::$variant => $name,)*
                }
            }
        }

        impl std::fmt::Display for $enum {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.$fn())
            }
        }
    };
}
pub(crate) use named_enum;

named_enum! {
    /// A binary operator in an expression.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum BinOp;
    /// The operator as written.
    fn symbol;
    Add "+"   "`+`";
    Sub "-"   "`-`";
    Mul "*"   "`*`";
    Div "/"   "`/`";
    Mod "MOD" "`MOD` (remainder)";
    Pow "**"  "`**` (LinuxCNC power)";
    And "AND" "`AND` (bitwise on integers in the Fanuc family, logical in LinuxCNC)";
    Or  "OR"  "`OR`";
    Xor "XOR" "`XOR`";
    Eq  "EQ"  "`EQ`";
    Ne  "NE"  "`NE`";
    Gt  "GT"  "`GT`";
    Ge  "GE"  "`GE`";
    Lt  "LT"  "`LT`";
    Le  "LE"  "`LE`";
}

named_enum! {
    /// A function applied to bracketed arguments.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Func;
    /// The function's usual name.
    fn name;
    Asin   "ASIN"   "Arc sine, degrees.";
    Acos   "ACOS"   "Arc cosine, degrees.";
    Atan   "ATAN"   "Arc tangent, degrees; two arguments (`ATAN[a]/[b]` or `ATAN[a,b]`) give atan2.";
    Sin    "SIN"    "Sine of degrees.";
    Cos    "COS"    "Cosine of degrees.";
    Tan    "TAN"    "Tangent of degrees.";
    Sqrt   "SQRT"   "Square root (also `SQR`).";
    Abs    "ABS"    "Absolute value.";
    Round  "ROUND"  "Round to the nearest integer (also `RND`).";
    Fix    "FIX"    "Round towards zero (Fanuc FIX rounds down: towards −∞ for negatives in LinuxCNC).";
    Fup    "FUP"    "Round up (away from zero in the Fanuc family).";
    Ln     "LN"     "Natural logarithm.";
    Exp    "EXP"    "e to the power.";
    Pow    "POW"    "`POW[a,b]`.";
    Bin    "BIN"    "BCD → binary.";
    Bcd    "BCD"    "Binary → BCD.";
    Exists "EXISTS" "LinuxCNC `EXISTS[#<name>]`.";
}

impl Func {
    /// Every function with each name the controls spell it with.
    pub fn names() -> impl Iterator<Item = (&'static str, Func)> {
        let aliases = [("SQR", Func::Sqrt), ("RND", Func::Round)];
        Func::ALL.into_iter().map(|f| (f.name(), f)).chain(aliases)
    }
}

/// One expression node.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A literal number.
    Num(f64),
    /// `#n`, `#[expr]`, `##n`: the variable whose number is the operand's value.
    Var(ExprId),
    /// LinuxCNC `#<name>` (stored lowercased, without blanks).
    Named(Box<str>),
    /// Unary minus.
    Neg(ExprId),
    /// A binary operation.
    Binary(BinOp, ExprId, ExprId),
    /// A function call (one argument, or two for ATAN/POW).
    Call(Func, ExprId, Option<ExprId>),
}

/// An expression node and the text it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprNode {
    /// The node.
    pub expr: Expr,
    /// Its text.
    pub span: Span,
}

/// A LinuxCNC O-word label: `o100`, `o<name>`, or a number computed when the line runs.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum OLabel {
    /// `o100`.
    Number(u32),
    /// `o<name>` (lowercased).
    Name(Box<str>),
    /// `o[#2 * 10]` or `o#1`: the number is the expression's value.
    Expr(ExprId),
}

/// What a LinuxCNC O-word line does.
#[derive(Debug, Clone, PartialEq)]
pub enum OWord {
    /// `sub`
    Sub,
    /// `endsub [expr]`
    EndSub(Option<ExprId>),
    /// `call [a] [b] …`
    Call(Vec<ExprId>),
    /// `return [expr]`
    Return(Option<ExprId>),
    /// `if [cond]`
    If(ExprId),
    /// `elseif [cond]`
    ElseIf(ExprId),
    /// `else`
    Else,
    /// `endif`
    EndIf,
    /// `while [cond]` (a loop head, or the tail of a `do` loop)
    While(ExprId),
    /// `endwhile`
    EndWhile,
    /// `do`
    Do,
    /// `repeat [count]`
    Repeat(ExprId),
    /// `endrepeat`
    EndRepeat,
    /// `break`
    Break,
    /// `continue`
    Continue,
}

/// A macro statement in a block.
#[derive(Debug, Clone, PartialEq)]
pub enum Statement {
    /// `#i = expr` (Syntec also `#i := expr`); `target` is a `Var` or `Named` node.
    Assign {
        /// The variable assigned.
        target: ExprId,
        /// The value.
        value: ExprId,
    },
    /// `GOTO n`.
    Goto {
        /// The sequence number jumped to.
        target: ExprId,
    },
    /// `IF [cond] GOTO n` or `IF [cond] THEN statement`.
    If {
        /// The condition.
        cond: ExprId,
        /// What runs when it holds (a `Goto` or an `Assign`).
        then: Box<Statement>,
    },
    /// `WHILE [cond] DOm` (`cond` is `None` for a bare `DOm`, an endless loop).
    While {
        /// The condition.
        cond: Option<ExprId>,
        /// The loop number m (1–3 in the Fanuc family).
        label: u8,
    },
    /// `ENDm`.
    End {
        /// The loop number m.
        label: u8,
    },
    /// A LinuxCNC O-word line.
    OWord {
        /// Its label.
        label: OLabel,
        /// What it does.
        kind: OWord,
    },
}

/// A program number: `O1234`, `:1234`, or LinuxCNC `O<name>`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ProgramNumber {
    /// `O1234` or `:1234`.
    Number(u32),
    /// `O<name>`.
    Name(Box<str>),
}

/// One block (a line, or part of a line ended by `;` in the Fanuc family).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// The block's text, from its first to its last byte (without the line ending).
    pub span: Span,
    /// 0-based line the block starts on.
    pub line: u32,
    /// The `N` sequence number plus one, if any ([`Block::number`]): four bytes rather than
    /// the eight of an `Option<u32>`, so that a block is 128 bytes, two cache lines.
    pub(crate) number: Option<NonZeroU32>,
    /// The address words in the order written (without `N` and `O`); up to four are stored in
    /// the block itself, so a typical CAM line needs no allocation of its own.
    pub words: SmallVec<[Word; 4]>,
    /// What few blocks have (program number, statements, comments, block-delete level, error
    /// mark), boxed so that every other block pays one pointer for it; `None`: none of them.
    pub(crate) extras: Option<Box<Extras>>,
}

/// What few blocks have besides their words (see [`Block::extras`]), each read by the
/// [`Block`] method of its name.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Extras {
    pub(crate) program: Option<ProgramNumber>,
    pub(crate) statements: Box<[Statement]>,
    pub(crate) comments: Box<[Span]>,
    pub(crate) block_delete: Option<u8>,
    pub(crate) has_error: bool,
}

impl Block {
    /// The first plain word with address `letter` (uppercase).
    pub fn word(&self, letter: u8) -> Option<&Word> {
        (self.words.iter()).find(|w| w.letter == letter && w.form == WordForm::Plain)
    }

    /// The comma word `,letter` if given.
    pub fn comma_word(&self, letter: u8) -> Option<&Word> {
        (self.words.iter()).find(|w| w.letter == letter && w.form == WordForm::Comma)
    }

    /// Whether the block has neither words nor statements (blank, comment or tape mark).
    pub fn is_empty(&self) -> bool {
        self.words.is_empty() && self.statements().is_empty()
    }

    /// Whether the block needs the macro evaluator (statements or expression-valued words).
    pub fn has_macro(&self) -> bool {
        !self.statements().is_empty() || self.words.iter().any(|w| w.expr.is_some())
    }

    /// The `N` sequence number, if any.
    #[inline]
    pub fn number(&self) -> Option<u32> {
        self.number.map(|n| n.get() - 1)
    }

    /// How the field holds sequence number `number` (`u32::MAX`, out of any control's range, is
    /// not kept).
    #[inline]
    pub(crate) fn stored_number(number: u32) -> Option<NonZeroU32> {
        number.checked_add(1).and_then(NonZeroU32::new)
    }

    /// Block-delete level: `/` is 1, `/n` is n; `None` when there is no slash.
    #[inline]
    pub fn block_delete(&self) -> Option<u8> {
        self.extras.as_deref()?.block_delete
    }

    /// Whether the parser found an error in this block (it is not executed).
    #[inline]
    pub fn has_error(&self) -> bool {
        self.extras.as_deref().is_some_and(|e| e.has_error)
    }

    /// The program number when the block starts a program (`O1234`, `:1234`).
    #[inline]
    pub fn program(&self) -> Option<&ProgramNumber> {
        self.extras.as_deref()?.program.as_ref()
    }

    /// Macro statements, in the order written (most blocks have none).
    #[inline]
    pub fn statements(&self) -> &[Statement] {
        self.extras.as_deref().map_or(&[], |e| &e.statements)
    }

    /// Spans of the comments in the block.
    #[inline]
    pub fn comments(&self) -> &[Span] {
        self.extras.as_deref().map_or(&[], |e| &e.comments)
    }

    /// The extras, to set one (program number, error mark …); made when the block has none yet.
    pub(crate) fn extras_mut(&mut self) -> &mut Extras {
        self.extras.get_or_insert_with(Box::default)
    }

    /// The bytes the block holds, its own and those it points to (for the parse's memory bound,
    /// [`MAX_PARSED_BYTES`](crate::MAX_PARSED_BYTES)).
    pub(crate) fn held_bytes(&self) -> usize {
        let spilled = usize::from(self.words.spilled()) * self.words.capacity();
        let extras = self.extras.as_deref().map_or(0, |e| {
            let statements: usize = e.statements.iter().map(Statement::held_bytes).sum();
            let name = match &e.program {
                Some(ProgramNumber::Name(name)) => name.len(),
                _ => 0,
            };
            size_of::<Extras>() + name + statements + size_of_val::<[Span]>(&e.comments)
        });
        size_of::<Block>() + spilled * size_of::<Word>() + extras
    }
}

impl Statement {
    /// The bytes the statement holds, its own and those it points to.
    fn held_bytes(&self) -> usize {
        size_of::<Statement>()
            + match self {
                Statement::If { then, .. } => then.held_bytes(),
                Statement::OWord { label, kind } => {
                    let name = match label {
                        OLabel::Name(name) => name.len(),
                        OLabel::Number(_) | OLabel::Expr(_) => 0,
                    };
                    let args = match kind {
                        OWord::Call(args) => args.capacity() * size_of::<ExprId>(),
                        _ => 0,
                    };
                    name + args
                }
                _ => 0,
            }
    }
}

impl ExprNode {
    /// The bytes the node holds, its own and a name's.
    pub(crate) fn held_bytes(&self) -> usize {
        size_of::<ExprNode>()
            + match &self.expr {
                Expr::Named(name) => name.len(),
                _ => 0,
            }
    }
}

/// A parsed program: its blocks, the diagnostics found while reading it, and its line table.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Program {
    /// The dialect the text was read as.
    pub dialect: Dialect,
    /// Every block, in text order (blank lines give no block).
    pub blocks: Vec<Block>,
    /// The expression arena that `ExprId`s index.
    pub exprs: Vec<ExprNode>,
    /// Problems found while reading, in text order.
    pub diagnostics: Vec<Diagnostic>,
    /// Line starts, for turning spans into line and column.
    pub lines: LineIndex,
    /// Whether the text is a Syntec `%@MACRO` program.
    pub syntec_macro: bool,
    /// The files linked after the program's own text (see [`Program::link`]).
    pub linked: Vec<crate::link::LinkedFile>,
    /// The calls whose program was found in a file that was not linked, and why (see
    /// [`Program::link_calls`]).
    pub unlinked: Vec<(crate::link::Missing, String)>,
}

impl Program {
    /// The expression node `id` refers to.
    pub fn expr(&self, id: ExprId) -> Option<&ExprNode> {
        self.exprs.get(id.index())
    }

    /// The bytes the parsed program holds, estimated from the sizes of its parts: its line
    /// table, blocks, expressions and diagnostics (see [`MAX_PARSED_BYTES`](crate::MAX_PARSED_BYTES)).
    pub(crate) fn held_bytes(&self) -> usize {
        let diagnostics: usize = self.diagnostics.iter().map(Diagnostic::held_bytes).sum();
        self.lines.line_count() * size_of::<u32>()
            + self.blocks.iter().map(Block::held_bytes).sum::<usize>()
            + self.exprs.iter().map(ExprNode::held_bytes).sum::<usize>()
            + diagnostics
    }
}
