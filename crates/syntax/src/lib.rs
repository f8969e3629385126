//! G-code text: decoding, the fault-tolerant parser, dialects and diagnostics. Parsing never
//! fails: each problem is a [`Diagnostic`] with a byte [`Span`]; reading resumes at the newline.

mod ast;
mod checks;
pub mod codes;
mod decode;
mod diagnostic;
mod dialect;
mod line_index;
mod link;
mod parser;
mod source;

pub use ast::{
    BinOp, Block, Expr, ExprId, ExprNode, Func, OLabel, OWord, Program, ProgramNumber, Statement,
    Word, WordForm,
};
pub use codes::{Code, CodeDef, DialectSet};
pub use decode::{Decoded, Encoding, MAX_FILE_BYTES, decode, decode_owned};
pub use diagnostic::{
    DIAGNOSTICS, Diagnostic, DiagnosticDef, EXCERPT_CHARS, Severity, Span, excerpt,
};
pub use dialect::{Dialect, Quantity, Rules, TimeRule, UnknownDialect};
pub use line_index::{LineCols, LineIndex};
pub use link::{
    CALLED_FILE_EXTENSIONS, LinkedFile, LinkedSource, Lookup, Missing, is_plain_file_name,
};
pub use parser::{MAX_PARSED_BYTES, ParseRun, ReadPoint, parse};
pub use source::LineSource;
