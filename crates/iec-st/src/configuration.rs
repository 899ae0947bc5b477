//! A checked `CONFIGURATION`: which PROGRAM instances run in which tasks of
//! which resource (IEC 61131-3, configuration elements). The interpreter
//! does not schedule tasks; the host reads them to run a program at its
//! task's interval.

/// A `CONFIGURATION`: one PLC system.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Configuration {
    /// The name as declared.
    pub name: String,
    /// Its resources in declaration order (one for a configuration that
    /// declares its tasks and programs directly).
    pub resources: Vec<Resource>,
}

/// A `RESOURCE`: one processing unit with its tasks and program instances.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Resource {
    /// The name as declared; `None` for the single resource of a
    /// configuration without `RESOURCE`.
    pub name: Option<String>,
    /// The resource type after `ON` (implementation-defined, e.g. `PLC`);
    /// `None` likewise.
    pub on: Option<String>,
    /// Its tasks in declaration order.
    pub tasks: Vec<Task>,
    /// Its program instances in declaration order.
    pub programs: Vec<ProgramInstance>,
}

/// A `TASK`: a periodic or free-running schedule for program instances.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Task {
    /// The name as declared.
    pub name: String,
    /// `INTERVAL`, in milliseconds (always > 0); `None` if not given.
    pub interval_ms: Option<u64>,
    /// `PRIORITY` (0 is the highest); `None` if not given.
    pub priority: Option<i64>,
}

/// A `PROGRAM` declaration in a resource: an instance of a PROGRAM POU.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProgramInstance {
    /// The instance name.
    pub name: String,
    /// The task after `WITH`, as declared in the same resource; `None` if
    /// not given.
    pub task: Option<String>,
    /// The PROGRAM POU, as declared (pass it to
    /// [`SourceFile::instantiate`](crate::SourceFile::instantiate)).
    pub pou: String,
}
