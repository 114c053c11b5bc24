//! The words of the `.ray` language, in one table that everyone reads: the
//! lexer takes its keywords from it, the parser's messages their categories,
//! the session its completion, colours and `:help` pages, and the hints the
//! words learners bring from elsewhere (the French course, other languages).

use std::fmt;

use super::token::Token;

pub mod highlight;

/// The part a keyword plays in the grammar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Starts a part of a file other than an instruction: `camera`, `ambient`, `light`, `proc`.
    Definition,
    /// Starts an instruction: `let`, `object`, `put`, `if`, `print`.
    Instruction,
    /// Starts a shape: `sphere`, `plane`, `box`.
    Shape,
    /// Starts a transformation or a group of objects.
    Transformation,
    /// One of the four parts of a texture (the table gives them in their order).
    Texture,
    /// Introduces a part inside a construct: `center`, `by`, `then`, `end`...
    Part,
    /// A built-in function: `sin`, `cos`, `sqrt`.
    Function,
    /// The constant `pi`.
    Constant,
}

/// What a word of the table is.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// A reserved word of SPEC 1.
    Keyword {
        /// The token the lexer gives it.
        token: Token,
        /// What it does in a program.
        role: Role,
        /// Whether it opens a construct that `end` closes.
        opens: bool,
    },
    /// A name the language gives a value without reserving it: `time`.
    Predefined,
    /// A word learners bring from elsewhere, where the language says `means`.
    Elsewhere {
        /// The word of the language it stands for.
        means: &'static str,
    },
    /// A function other languages have and this one has not.
    MissingFunction,
}

/// One word and what to say about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Word {
    /// How it is written.
    pub text: &'static str,
    /// What it is.
    pub kind: Kind,
    /// For a word of the language, what it is in a few words; for a word from
    /// elsewhere, where it comes from; for a missing function, how to do
    /// without it (empty when there is no way).
    pub about: &'static str,
    /// The `:help` page that explains a word of the language (empty for the others).
    pub topic: &'static str,
}

const fn keyword(text: &'static str, token: Token, role: Role, topic: &'static str, about: &'static str) -> Word {
    Word { text, kind: Kind::Keyword { token, role, opens: false }, about, topic }
}

const fn opener(text: &'static str, token: Token, role: Role, about: &'static str) -> Word {
    Word { text, kind: Kind::Keyword { token, role, opens: true }, about, topic: text }
}

const fn elsewhere(text: &'static str, means: &'static str, about: &'static str) -> Word {
    Word { text, kind: Kind::Elsewhere { means }, about, topic: "" }
}

const fn french(text: &'static str, means: &'static str) -> Word {
    elsewhere(text, means, "French")
}

const fn missing_function(text: &'static str, instead: &'static str) -> Word {
    Word { text, kind: Kind::MissingFunction, about: instead, topic: "" }
}

use Role::{Constant, Definition, Function, Instruction, Part, Shape, Texture, Transformation};

/// Every word, the language's own in the order of the grammar (SPEC 2).
pub const WORDS: &[Word] = &[
    opener("camera", Token::Camera, Definition, "where the eye is and how wide it sees"),
    keyword("distance", Token::Distance, Part, "camera", "how far the camera is from the origin"),
    keyword("angle", Token::Angle, Part, "camera", "how wide the camera sees, in radians"),
    keyword("ambient", Token::Ambient, Definition, "ambient", "light that reaches every surface, even in shadow"),
    opener("light", Token::Light, Definition, "a far away light shining from one direction"),
    keyword("vector", Token::Vector, Part, "light", "the three angles that turn a light's direction"),
    keyword("rotation", Token::Rotation, Part, "rotation", "three angles: about x, then y, then z"),
    keyword("intensity", Token::Intensity, Part, "light", "how strong a light is, 0 to 1"),
    opener("proc", Token::Proc, Definition, "a procedure: instructions to run again with other numbers"),
    keyword("let", Token::Let, Instruction, "let", "gives a number a name"),
    keyword("object", Token::Object, Instruction, "object", "gives an object a name"),
    keyword("put", Token::Put, Instruction, "put", "adds an object to the scene"),
    opener("if", Token::If, Instruction, "does something only when a condition holds"),
    keyword("print", Token::Print, Instruction, "print", "shows values while the program runs (an extension)"),
    keyword("then", Token::Then, Part, "if", "what an `if` does when its condition holds"),
    keyword("else", Token::Else, Part, "if", "what an `if` does when its condition does not hold"),
    keyword("end", Token::End, Part, "end", "closes the construct opened last"),
    opener("sphere", Token::Sphere, Shape, "a ball: center and radius"),
    keyword("center", Token::Center, Part, "sphere", "the centre of a sphere or a box"),
    keyword("radius", Token::Radius, Part, "sphere", "the size of a sphere"),
    opener("plane", Token::Plane, Shape, "a flat surface that goes on forever"),
    keyword("shift", Token::Shift, Part, "plane", "how far a plane is moved along the way it faces"),
    opener("box", Token::Box, Shape, "a box: center and sizes along x, y and z"),
    keyword("length", Token::Length, Part, "box", "the sizes of a box along x, y and z"),
    keyword("kd", Token::Kd, Texture, "texture", "how much light a surface spreads around, 0 to 1"),
    keyword("ks", Token::Ks, Texture, "texture", "how shiny a surface is, 0 to 1"),
    keyword("phong", Token::Phong, Texture, "texture", "how small the highlight is (more than 0)"),
    keyword("color", Token::Color, Texture, "texture", "red, green, blue, each 0 to 255"),
    opener("translate", Token::Translate, Transformation, "moves an object"),
    opener("rotate", Token::Rotate, Transformation, "turns an object about the origin"),
    opener("scale", Token::Scale, Transformation, "makes an object bigger or smaller"),
    opener("group", Token::Group, Transformation, "several objects treated as one"),
    keyword("by", Token::By, Part, "by", "how much `translate`, `rotate` and `scale` change an object"),
    keyword("sin", Token::Sin, Function, "functions", "the sine of an angle in radians"),
    keyword("cos", Token::Cos, Function, "functions", "the cosine of an angle in radians"),
    keyword("sqrt", Token::Sqrt, Function, "functions", "the square root"),
    keyword("pi", Token::Pi, Constant, "pi", "the number pi, half a turn in radians"),
    Word { text: "time", kind: Kind::Predefined, about: "the frame number of an animation", topic: "time" },
    // The words of the French course for what the language writes in English.
    french("caméra", "camera"),
    french("ambiante", "ambient"),
    french("lumière", "light"),
    french("lumiere", "light"),
    french("vecteur", "vector"),
    french("intensité", "intensity"),
    french("intensite", "intensity"),
    french("procédure", "proc"),
    french("soit", "let"),
    french("objet", "object"),
    french("si", "if"),
    french("alors", "then"),
    french("sinon", "else"),
    french("fin", "end"),
    french("sphère", "sphere"),
    french("rayon", "radius"),
    french("plan", "plane"),
    french("décalage", "shift"),
    french("decalage", "shift"),
    french("boîte", "box"),
    french("boite", "box"),
    french("longueur", "length"),
    french("couleur", "color"),
    french("groupe", "group"),
    french("translation", "translate"),
    french("dilatation", "scale"),
    french("homothétie", "scale"),
    french("homothetie", "scale"),
    french("racine", "sqrt"),
    elsewhere("centre", "center", "the French and British spelling"),
    elsewhere("colour", "color", "the British spelling"),
    elsewhere("cube", "box", "the course's word for a box"),
    elsewhere("procedure", "proc", "the long form"),
    elsewhere("function", "proc", "what other languages call a procedure"),
    elsewhere("def", "proc", "what other languages call a procedure"),
    elsewhere("var", "let", "what other languages use for a variable"),
    elsewhere("endif", "end", "what other languages use to close an `if`"),
    // Functions of other languages, and how to do without.
    missing_function("tan", "`tan(x)` is `sin(x) / cos(x)`"),
    missing_function("abs", "`abs(x)` is `sqrt(x * x)`"),
    missing_function("pow", "a square is `x * x`"),
    missing_function("sqr", "a square is `x * x`"),
    missing_function("exp", ""),
    missing_function("log", ""),
    missing_function("ln", ""),
    missing_function("atan", ""),
    missing_function("asin", ""),
    missing_function("acos", ""),
    missing_function("min", "use an `if` to choose"),
    missing_function("max", "use an `if` to choose"),
    missing_function("floor", ""),
    missing_function("round", ""),
];

/// The row of `text`, if the table has one.
pub fn lookup(text: &str) -> Option<&'static Word> {
    WORDS.iter().find(|word| word.text == text)
}

/// The keywords of the language, with their tokens, in the table's order.
pub fn keywords() -> impl Iterator<Item = (&'static Word, &'static Token)> {
    WORDS.iter().filter_map(|word| match &word.kind {
        Kind::Keyword { token, .. } => Some((word, token)),
        _ => None,
    })
}

/// The names of the keywords that play `role`, in the table's order.
pub fn with_role(role: Role) -> impl Iterator<Item = &'static str> {
    keywords().filter(move |(word, _)| word.role() == Some(role)).map(|(word, _)| word.text)
}

/// The words of the language itself: its keywords and `time`.
pub fn language() -> impl Iterator<Item = &'static Word> {
    WORDS.iter().filter(|word| !word.topic.is_empty())
}

impl Word {
    /// The keyword's role in the grammar (`None` for other words).
    pub fn role(&self) -> Option<Role> {
        match self.kind {
            Kind::Keyword { role, .. } => Some(role),
            _ => None,
        }
    }

    /// Whether the word opens a construct that `end` closes.
    pub fn opens(&self) -> bool {
        matches!(self.kind, Kind::Keyword { opens: true, .. })
    }
}

/// The keyword spelt `text` in another case (`CAMERA`, `Sphere`), if any.
pub fn in_lower_case(text: &str) -> Option<&'static str> {
    let lower = text.to_ascii_lowercase();
    keywords().map(|(word, _)| word.text).find(|keyword| *keyword == lower && *keyword != text)
}

/// What to say about a name that is not the language's (a word from the
/// French course, a keyword in capitals), if the table knows it.
pub fn hint_for_name(text: &str) -> Option<String> {
    if let Some(keyword) = in_lower_case(text) {
        return Some(format!("keywords are written in lower case: `{keyword}`"));
    }
    let (word, means) = from_elsewhere(text)?;
    Some(format!("`{text}` is {}: the keyword is `{means}`", word.about))
}

/// The keyword that [`hint_for_name`] proposes for `text`, if it proposes
/// one: the keyword in lower case, or the one a word from elsewhere means.
pub fn keyword_meant(text: &str) -> Option<&'static str> {
    in_lower_case(text).or_else(|| from_elsewhere(text).map(|(_, means)| means))
}

/// The word of the table from another language that `text` is (in any
/// case), and the keyword it means.
fn from_elsewhere(text: &str) -> Option<(&'static Word, &'static str)> {
    let word = lookup(text).or_else(|| lookup(&text.to_lowercase()))?;
    match word.kind {
        Kind::Elsewhere { means } => Some((word, means)),
        _ => None,
    }
}

/// What to say about `name(...)` in an expression: the functions that exist,
/// and how to do without `name` if the table knows how.
pub fn hint_for_function(name: &str) -> String {
    let functions: Vec<String> = with_role(Function).map(|f| format!("`{f}`")).collect();
    let list = match functions.as_slice() {
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
        [] => String::new(),
    };
    let instead = lookup(name).filter(|word| word.kind == Kind::MissingFunction && !word.about.is_empty());
    match instead {
        Some(word) => format!("there is no `{name}`; the functions are {list}: {}", word.about),
        None => format!("there is no function `{name}`; the functions are {list}"),
    }
}

/// The names of all keywords, for "did you mean ...?" suggestions.
pub fn keyword_names() -> impl Iterator<Item = &'static str> {
    keywords().map(|(word, _)| word.text)
}

/// The keyword token spelt `word`, if `word` is a keyword.
pub fn keyword_token(word: &str) -> Option<Token> {
    keywords().find(|(row, _)| row.text == word).map(|(_, token)| token.clone())
}

impl Token {
    /// How the token is written, for keywords and symbols; `None` for
    /// numbers and names, whose text depends on the source.
    pub fn spelling(&self) -> Option<&'static str> {
        let symbol = match self {
            Token::Number(_) | Token::Ident(_) => return None,
            Token::Plus => "+",
            Token::Minus => "-",
            Token::Star => "*",
            Token::Slash => "/",
            Token::LParen => "(",
            Token::RParen => ")",
            Token::Comma => ",",
            Token::Eq => "=",
            Token::Ne => "!=",
            Token::Lt => "<",
            Token::Le => "<=",
            Token::Gt => ">",
            Token::Ge => ">=",
            Token::And => "&",
            Token::Or => "|",
            Token::Bang => "!",
            keyword => return keywords().find(|(_, token)| *token == keyword).map(|(word, _)| word.text),
        };
        Some(symbol)
    }

    /// Whether the token is a keyword of SPEC 1.
    pub fn is_keyword(&self) -> bool {
        keywords().any(|(_, token)| token == self)
    }
}

impl fmt::Display for Token {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Number(value) => write!(f, "{value}"),
            Token::Ident(name) => f.write_str(name),
            other => f.write_str(other.spelling().unwrap_or("?")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_word_is_in_the_table_once() {
        for (index, word) in WORDS.iter().enumerate() {
            assert!(WORDS[..index].iter().all(|other| other.text != word.text), "`{}` twice", word.text);
        }
    }

    #[test]
    fn words_from_elsewhere_mean_keywords() {
        for word in WORDS {
            if let Kind::Elsewhere { means } = word.kind {
                assert!(lookup(means).is_some_and(|w| w.role().is_some()), "`{}` means `{means}`", word.text);
            }
        }
    }

    #[test]
    fn the_texture_words_are_in_their_order() {
        assert_eq!(with_role(Texture).collect::<Vec<_>>(), ["kd", "ks", "phong", "color"]);
    }

    /// The class of a word of each class (the words from elsewhere are
    /// names); tools/generate checks what each highlighter gives a class.
    #[test]
    fn classes_of_words() {
        use highlight::Class::*;
        let rows = [
            ("if", Some(Control)),
            ("else", Some(Control)),
            ("end", Some(Control)),
            ("proc", Some(Control)),
            ("camera", Some(Definition)),
            ("put", Some(Instruction)),
            ("box", Some(Shape)),
            ("group", Some(Transformation)),
            ("radius", Some(Part)),
            ("phong", Some(Texture)),
            ("sqrt", Some(Function)),
            ("pi", Some(Constant)),
            ("time", Some(Predefined)),
            ("colour", None),
        ];
        for (text, class) in rows {
            let word = lookup(text).expect("a word of the table");
            assert_eq!(highlight::class(word), class, "`{text}`");
        }
        for topic in highlight::CONTROL_TOPICS {
            assert!(lookup(topic).is_some_and(|word| word.topic == topic), "`{topic}` is a help page");
        }
    }

    #[test]
    fn hints_for_names() {
        assert_eq!(hint_for_name("CAMERA").as_deref(), Some("keywords are written in lower case: `camera`"));
        assert_eq!(hint_for_name("Put").as_deref(), Some("keywords are written in lower case: `put`"));
        assert_eq!(hint_for_name("rayon").as_deref(), Some("`rayon` is French: the keyword is `radius`"));
        assert_eq!(hint_for_name("Couleur").as_deref(), Some("`Couleur` is French: the keyword is `color`"));
        assert_eq!(hint_for_name("ball"), None);
        assert_eq!(hint_for_name("sphere"), None);
        assert_eq!(keyword_meant("Couleur"), Some("color"));
        assert_eq!(keyword_meant("CAMERA"), Some("camera"));
        assert_eq!(keyword_meant("ball"), None);
    }

    #[test]
    fn hints_for_functions() {
        assert_eq!(
            hint_for_function("tan"),
            "there is no `tan`; the functions are `sin`, `cos` and `sqrt`: `tan(x)` is `sin(x) / cos(x)`"
        );
        assert_eq!(hint_for_function("exp"), "there is no function `exp`; the functions are `sin`, `cos` and `sqrt`");
    }
}
