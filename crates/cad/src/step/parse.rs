//! ISO 10303-21 (the STEP physical file) parsed into instances: `#id = NAME(params);` and
//! complex instances `#id = (A(params) B(params) …);`. O(size of the file).

use std::collections::BTreeMap;

use crate::number::parse_real;
use crate::{Error, Result};

const FORMAT: &str = "STEP";

/// The deepest nesting of parameter lists read. Part 21 files written by CAD systems nest a
/// few levels (a surface's control points are a list of lists); a bound keeps a hostile file
/// from overflowing the stack, since the parser recurses once per level.
const DEEPEST: usize = 64;

/// A parameter value.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Value {
    Integer(i64),
    Real(f64),
    Text(String),
    Enum(String),
    Ref(usize),
    /// `$`, an unset optional value.
    Unset,
    /// `*`, a value derived from a supertype.
    Derived,
    List(Vec<Value>),
    /// A typed value, e.g. `LENGTH_MEASURE(1.E-07)`.
    Typed(String, Vec<Value>),
}

impl Value {
    pub(crate) fn number(&self) -> Option<f64> {
        match self {
            Value::Integer(v) => Some(*v as f64),
            Value::Real(v) => Some(*v),
            Value::Typed(_, inner) if inner.len() == 1 => inner[0].number(),
            _ => None,
        }
    }

    pub(crate) fn list(&self) -> Option<&[Value]> {
        match self {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    pub(crate) fn reference(&self) -> Option<usize> {
        match self {
            Value::Ref(id) => Some(*id),
            _ => None,
        }
    }

    pub(crate) fn text(&self) -> Option<&str> {
        match self {
            Value::Text(t) => Some(t),
            _ => None,
        }
    }

    pub(crate) fn enumeration(&self) -> Option<&str> {
        match self {
            Value::Enum(e) => Some(e),
            _ => None,
        }
    }
}

/// One instance: its entity parts (one for a simple instance) and the line it starts on.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Instance {
    pub(crate) parts: Vec<(String, Vec<Value>)>,
    pub(crate) line: usize,
}

impl Instance {
    /// The parameters of the part named `name`, if the instance has it.
    pub(crate) fn part(&self, name: &str) -> Option<&[Value]> {
        self.parts
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }
}

struct Lexer<'a> {
    bytes: &'a [u8],
    at: usize,
    line: usize,
    /// How many parameter lists are open.
    depth: usize,
}

impl Lexer<'_> {
    fn error(&self, message: impl Into<String>) -> Error {
        Error::parse(FORMAT, self.line, message)
    }

    /// Skips white space and comments.
    fn skip(&mut self) -> Result<()> {
        loop {
            match self.bytes.get(self.at) {
                Some(b'\n') => {
                    self.line += 1;
                    self.at += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.at += 1,
                Some(b'/') if self.bytes.get(self.at + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.at += 2;
                    loop {
                        match self.bytes.get(self.at) {
                            None => {
                                return Err(Error::parse(FORMAT, start, "a comment is not closed"));
                            }
                            Some(b'*') if self.bytes.get(self.at + 1) == Some(&b'/') => {
                                self.at += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.at += 1;
                            }
                            Some(_) => self.at += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn peek(&mut self) -> Result<Option<u8>> {
        self.skip()?;
        Ok(self.bytes.get(self.at).copied())
    }

    fn expect(&mut self, byte: u8) -> Result<()> {
        match self.peek()? {
            Some(b) if b == byte => {
                self.at += 1;
                Ok(())
            }
            Some(b) => Err(self.error(format!("expected `{}`, found `{}`", byte as char, b as char))),
            None => Err(self.error(format!("expected `{}`, found the end of the file", byte as char))),
        }
    }

    fn keyword(&mut self) -> Result<String> {
        self.skip()?;
        let start = self.at;
        while self
            .bytes
            .get(self.at)
            .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_' || *c == b'!')
        {
            self.at += 1;
        }
        if start == self.at {
            return Err(self.error("expected an entity name"));
        }
        Ok(String::from_utf8_lossy(&self.bytes[start..self.at]).to_ascii_uppercase())
    }

    fn integer(&mut self) -> Result<usize> {
        let start = self.at;
        while self.bytes.get(self.at).is_some_and(u8::is_ascii_digit) {
            self.at += 1;
        }
        std::str::from_utf8(&self.bytes[start..self.at])
            .ok()
            .and_then(|t| t.parse().ok())
            .ok_or_else(|| self.error("expected an instance number"))
    }

    fn value(&mut self) -> Result<Value> {
        let Some(c) = self.peek()? else {
            return Err(self.error("a parameter list is not closed"));
        };
        match c {
            b'#' => {
                self.at += 1;
                Ok(Value::Ref(self.integer()?))
            }
            b'$' => {
                self.at += 1;
                Ok(Value::Unset)
            }
            b'*' => {
                self.at += 1;
                Ok(Value::Derived)
            }
            b'\'' => {
                self.at += 1;
                let mut text = Vec::new();
                loop {
                    match self.bytes.get(self.at) {
                        None => return Err(self.error("a string is not closed")),
                        Some(b'\'') if self.bytes.get(self.at + 1) == Some(&b'\'') => {
                            text.push(b'\'');
                            self.at += 2;
                        }
                        Some(b'\'') => {
                            self.at += 1;
                            break;
                        }
                        Some(&b) => {
                            if b == b'\n' {
                                self.line += 1;
                            }
                            text.push(b);
                            self.at += 1;
                        }
                    }
                }
                Ok(Value::Text(String::from_utf8_lossy(&text).into_owned()))
            }
            b'"' => {
                self.at += 1;
                let start = self.at;
                while self.bytes.get(self.at).is_some_and(|&b| b != b'"') {
                    self.at += 1;
                }
                let text = String::from_utf8_lossy(&self.bytes[start..self.at]).into_owned();
                self.expect(b'"')?;
                Ok(Value::Text(text))
            }
            b'.' => {
                self.at += 1;
                let start = self.at;
                while self
                    .bytes
                    .get(self.at)
                    .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
                {
                    self.at += 1;
                }
                let name = String::from_utf8_lossy(&self.bytes[start..self.at]).to_ascii_uppercase();
                self.expect(b'.')?;
                Ok(Value::Enum(name))
            }
            b'(' => {
                self.at += 1;
                Ok(Value::List(self.values_until_close()?))
            }
            b'+' | b'-' | b'0'..=b'9' => {
                let start = self.at;
                self.at += 1;
                while self
                    .bytes
                    .get(self.at)
                    .is_some_and(|c| c.is_ascii_digit() || b".eEdD+-".contains(c))
                {
                    self.at += 1;
                }
                let text = std::str::from_utf8(&self.bytes[start..self.at]).unwrap_or("");
                if let Ok(v) = text.parse::<i64>() {
                    return Ok(Value::Integer(v));
                }
                parse_real(text)
                    .map(Value::Real)
                    .ok_or_else(|| self.error(format!("`{text}` is not a number")))
            }
            c if c.is_ascii_alphabetic() => {
                let name = self.keyword()?;
                self.expect(b'(')?;
                Ok(Value::Typed(name, self.values_until_close()?))
            }
            c => Err(self.error(format!("unexpected `{}` in a parameter list", c as char))),
        }
    }

    /// Values separated by commas, after an opening parenthesis, through the closing one.
    /// Refuses lists nested deeper than [`DEEPEST`].
    fn values_until_close(&mut self) -> Result<Vec<Value>> {
        if self.depth >= DEEPEST {
            return Err(self.error(format!("parameter lists nested deeper than {DEEPEST}")));
        }
        self.depth += 1;
        let out = self.values_until_close_inner();
        self.depth -= 1;
        out
    }

    fn values_until_close_inner(&mut self) -> Result<Vec<Value>> {
        let mut out = Vec::new();
        if self.peek()? == Some(b')') {
            self.at += 1;
            return Ok(out);
        }
        loop {
            out.push(self.value()?);
            match self.peek()? {
                Some(b',') => self.at += 1,
                Some(b')') => {
                    self.at += 1;
                    return Ok(out);
                }
                Some(c) => {
                    return Err(self.error(format!("expected `,` or `)`, found `{}`", c as char)));
                }
                None => return Err(self.error("a parameter list is not closed")),
            }
        }
    }

    /// Whether the next word is `word` (then consumed) — for `DATA;`, `ENDSEC;`.
    fn word(&mut self, word: &str) -> Result<bool> {
        self.skip()?;
        let end = self.at + word.len();
        if self
            .bytes
            .get(self.at..end)
            .is_some_and(|b| b.eq_ignore_ascii_case(word.as_bytes()))
        {
            self.at = end;
            return Ok(true);
        }
        Ok(false)
    }
}

/// Finds `DATA;` outside strings and comments: the offset after it and the line it is on.
fn data_section(text: &str) -> Option<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut lexer = Lexer {
        bytes,
        at: 0,
        line: 1,
        depth: 0,
    };
    loop {
        lexer.skip().ok()?;
        match bytes.get(lexer.at)? {
            b'\'' => {
                lexer.value().ok()?;
            }
            _ => {
                let boundary = lexer.at == 0
                    || !bytes
                        .get(lexer.at - 1)
                        .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_');
                if boundary && lexer.word("DATA").ok()? {
                    lexer.skip().ok()?;
                    if bytes.get(lexer.at) == Some(&b';') {
                        return Some((lexer.at + 1, lexer.line));
                    }
                } else {
                    lexer.at += 1;
                }
            }
        }
    }
}

/// The instances of the DATA section by instance number. Fails with [`Error::Parse`] naming
/// the line on anything that is not Part 21 syntax.
pub(crate) fn parse(text: &str) -> Result<BTreeMap<usize, Instance>> {
    if !text
        .trim_start_matches('\u{feff}')
        .trim_start()
        .starts_with("ISO-10303-21")
    {
        return Err(Error::parse(FORMAT, 1, "a STEP file starts with `ISO-10303-21;`"));
    }
    let (start, line) =
        data_section(text).ok_or_else(|| Error::parse(FORMAT, 1, "the file has no `DATA;` section"))?;
    let mut lexer = Lexer {
        bytes: text.as_bytes(),
        at: start,
        line,
        depth: 0,
    };
    let mut instances = BTreeMap::new();
    loop {
        if lexer.word("ENDSEC")? {
            break;
        }
        match lexer.peek()? {
            None => return Err(lexer.error("the DATA section has no `ENDSEC;`")),
            Some(b'#') => {}
            Some(c) => {
                return Err(lexer.error(format!("expected an instance `#n = …;`, found `{}`", c as char)));
            }
        }
        let instance_line = lexer.line;
        lexer.at += 1;
        let id = lexer.integer()?;
        lexer.expect(b'=')?;
        let mut parts = Vec::new();
        if lexer.peek()? == Some(b'(') {
            lexer.at += 1;
            while lexer.peek()? != Some(b')') {
                let name = lexer.keyword()?;
                lexer.expect(b'(')?;
                parts.push((name, lexer.values_until_close()?));
            }
            lexer.at += 1;
        } else {
            let name = lexer.keyword()?;
            lexer.expect(b'(')?;
            parts.push((name, lexer.values_until_close()?));
        }
        lexer.expect(b';')?;
        if instances
            .insert(
                id,
                Instance {
                    parts,
                    line: instance_line,
                },
            )
            .is_some()
        {
            return Err(Error::parse(
                FORMAT,
                instance_line,
                format!("instance #{id} is defined twice"),
            ));
        }
    }
    Ok(instances)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_and_complex_instances_parse() {
        let text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('DATA;'),'2;1');\nENDSEC;\nDATA;\n\
            #1 = CARTESIAN_POINT('it''s',(1.,-2.5E-3,3));\n/* a comment #9 = X(); */\n\
            #2 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n\
            #3 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#2,'a',$);\nENDSEC;\nEND-ISO-10303-21;\n";
        let instances = parse(text).unwrap();
        assert_eq!(instances.len(), 3);
        let point = &instances[&1];
        assert_eq!(point.parts.len(), 1);
        assert_eq!(point.parts[0].0, "CARTESIAN_POINT");
        assert_eq!(point.line, 6);
        let params = point.part("CARTESIAN_POINT").unwrap();
        assert_eq!(params[0].text(), Some("it's"));
        let coords: Vec<f64> = params[1]
            .list()
            .unwrap()
            .iter()
            .filter_map(Value::number)
            .collect();
        assert_eq!(coords, vec![1.0, -2.5e-3, 3.0]);
        let unit = &instances[&2];
        assert_eq!(unit.parts.len(), 3);
        assert_eq!(unit.part("SI_UNIT").unwrap()[0].enumeration(), Some("MILLI"));
        assert_eq!(unit.part("NAMED_UNIT").unwrap()[0], Value::Derived);
        assert_eq!(instances[&3].line, 9);
        assert_eq!(instances[&3].parts[0].1[0].number(), Some(1e-7));
        assert_eq!(instances[&3].parts[0].1[3], Value::Unset);
    }

    #[test]
    fn broken_files_name_the_line() {
        let bad = "ISO-10303-21;\nDATA;\n#1 = CARTESIAN_POINT('',(1.,2.);\nENDSEC;\n";
        match parse(bad) {
            Err(Error::Parse { line, .. }) => assert_eq!(line, 3),
            other => panic!("{other:?}"),
        }
        assert!(matches!(parse("hello"), Err(Error::Parse { line: 1, .. })));
        assert!(matches!(
            parse("ISO-10303-21;\nDATA;\n#1 = A();\n#1 = B();\nENDSEC;"),
            Err(Error::Parse { line: 4, .. })
        ));
    }
}
