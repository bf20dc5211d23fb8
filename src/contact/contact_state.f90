!> Contact state: the deck's contact groups, the interfaces (whole surfaces,
!> this part's local surfaces and pairs, per-cycle geometry caches, the
!> diagnostics), the contact of a run (contact index space, owned nodes, the
!> RCB part's local set and migration plan), and the abstract contact method
!> (contact_method_t) that DAM (contact_dam) and DLM (contact_dlm) extend.
!> Everything here is method-neutral: a method's own arrays live in its type,
!> and what differs between methods is a deferred procedure, so a third
!> method is one new module and one case in contact_factory (docs/design.md).
!> The abstract type is declared here, with the interface and the contact it
!> works on, because its procedures take both and an interface holds its
!> method. Shared by contact_parts (search on the RCB parts, migration) and
!> contact_enforce (the rounds). No MPI, no I/O.
module contact_state
  use core_kinds, only: rk, ik, i8
  use core_exact_sum, only: exact_sum_t
  use mesh_global, only: NAME_LEN
  use contact_surface, only: contact_surface_t, nodal_areas
  use contact_geometry, only: segment_facets, triangle_unit_normal, triangle_vector_area, &
      quad_unit_normal, SEGMENT_FACET_COUNT
  use contact_records, only: records_t
  use core_sort, only: sorted_find
  use parallel_env, only: traffic_t
  implicit none
  private
  public :: capture_of, key_node, geometry_free, geometry_update, recovery_allowance, &
      recovery_excess, recovery_speed_of, owned_index

  !> Pair kinds of a method's search (contact_method_t%pair_kind): segment
  !> pairs (a segment of a, a segment of b: keyed by the a-segment's first
  !> node) or node-segment pairs (a node of a, a segment of b: keyed by the
  !> node).
  integer, parameter, public :: PAIR_SEGMENTS = 1, PAIR_NODE_SEGMENT = 2
  !> Most rounds a method runs in a stage (records to the owners and back).
  integer, parameter, public :: MAX_ROUNDS = 2
  !> Diagnostic columns per contact pair.
  !> active: enforced pairs (DLM facet pairs, DAM slave nodes); force: total
  !> normal force; pen_max, pen_rms: largest and RMS penetration at t^n;
  !> released: nodes in contact last step and not now; dmom: momentum the
  !> contact forces added over the step (zero to round-off for DLM).
  !> force_x, _y, _z: contact force on surface a (the DAM slave side) in the
  !> corrector; work: contact work of the interface so far; audit_*: the
  !> geometric audit (contact_monitor) at the last search or dump:
  !> audit_pen_max_a / _b the deepest node of surface a / b beyond its
  !> initial offset, audit_count_a / _b the nodes deeper than the tolerance,
  !> unheld: those of them in no enforced pair (DAM: slave nodes only; a
  !> master node's penetration is in audit_*_b).
  integer, parameter, public :: CONTACT_DIAG_COUNT = 17
  character(len=*), parameter, public :: CONTACT_DIAG_NAMES(CONTACT_DIAG_COUNT) = [ &
      character(len=16) :: 'active', 'force', 'pen_max', 'pen_rms', 'released', &
      'dmom_x', 'dmom_y', 'dmom_z', 'force_x', 'force_y', 'force_z', 'work', &
      'audit_pen_max_a', 'audit_pen_max_b', 'audit_count_a', 'audit_count_b', 'unheld']
  !> Positions of the monitor's columns in diag.
  integer, parameter, public :: DIAG_FORCE = 9, DIAG_WORK = 12, DIAG_AUDIT = 13

  !> Facets facing each other: n_a . n_b below this (DAM facet pairs, DLM
  !> segment pairs in self-contact, where it keeps neighbours across a
  !> concave corner of one surface apart).
  real(rk), parameter, public :: FACING = -0.2_rk
  !> DLM segment pairs between two surfaces: any that face each other (a
  !> convex edge's side faces meet a dented plate nearly at right angles,
  !> docs/contact.md 9.3).
  real(rk), parameter, public :: FACING_SURFACES = 0.0_rk
  !> Overlaps smaller than this fraction of the smaller facet's area are
  !> ignored: slivers between facets of neighbouring nodes that coincide in
  !> one projection but not in the slightly tilted common plane of another
  !> segment pair (relative size tilt x penetration / zone, ~1e-12 on the
  !> mirror test). They carry less than this share of a node's force.
  real(rk), parameter, public :: AREA_TOLERANCE = 1.0e-8_rk
  !> Share of the audit's tolerance (contact_audit) a pair may keep without
  !> recovery (DLM's facet pairs, DAM's slave nodes): the recovery starts well
  !> below the tolerance, so a pair it holds keeps a margin for one step's
  !> overshoot.
  real(rk), parameter, public :: ALLOWANCE_SHARE = 0.4_rk
  !> The recovery's separating speed is at most this share of the contact's
  !> largest node speed (recovery_speed_of).
  real(rk), parameter :: RECOVERY_SPEED_SHARE = 1.0_rk
  !> The size part of that allowance, ALLOWANCE_SHARE x SIZE_FRACTION (0.05)
  !> of the size (square root of the area) of the smaller of the two sides.
  real(rk), parameter :: SIZE_ALLOWANCE = 0.02_rk
  !> A node whose motion is prescribed (a velocity boundary: a driven platen,
  !> a welded end) is rigid for the contact: its mass is scaled by this
  !> factor, so a merge or a multiplier changes its velocity by 1e-12 of the
  !> other side's change and the other side takes the whole correction.
  !> (Without it the contact slows the driven node, the boundary restores it,
  !> and the node sinks into what it pushes: the folding tube's driven rim
  !> went a wall thickness into the tube's own fold.)
  real(rk), parameter, public :: RIGID_MASS_FACTOR = 1.0e12_rk

  !> One RCB part's sums of a stage for an interface (reduced over the
  !> parts into the diagnostics).
  type, public :: step_sums_t
    real(rk) :: active = 0.0_rk !< enforced pairs: DLM facet pairs, DAM slave nodes
    real(rk) :: force = 0.0_rk !< total normal force
    real(rk) :: pen_max = 0.0_rk !< largest penetration of an enforced pair at t^n
    real(rk) :: pen_sq = 0.0_rk !< sum of squared penetrations (DLM: area-weighted)
    real(rk) :: weight = 0.0_rk !< their weight: DLM overlap area, DAM penetrating slaves
    real(rk) :: dmom(3) = 0.0_rk !< momentum the contact forces added
  end type step_sums_t

  !> Length of a contact surface's list of face-set names.
  integer, parameter, public :: SURFACE_LEN = 256

  !> One &contact group as read from the deck.
  type, public :: contact_spec_t
    character(len=NAME_LEN) :: name = ''
    character(len=SURFACE_LEN) :: surface_a = '' !< face sets (names, blank or comma separated)
    character(len=SURFACE_LEN) :: surface_b = '' !< face sets (= surface_a: self-contact)
    character(len=8) :: method = '' !< 'dam' or 'dlm'
    character(len=1) :: master = 'b' !< DAM master side
    character(len=8) :: normal = 'master' !< DAM: contact normal of a slave, 'master' or 'slave'
    character(len=12) :: form = 'velocity' !< DLM: coordinate, velocity, combined
    real(rk) :: capture = 0.0_rk !< largest open gap treated as contact (0 = automatic)
    !> audit: penetration a node may have (0 = automatic: the larger of 5% of
    !> the smaller adjacent segment and the opposite surface's sagitta)
    real(rk) :: penetration_tolerance = 0.0_rk
    character(len=8) :: on_penetration = 'warn' !< audit violation: 'warn' or 'stop'
    !> penetration at set-up beyond the tolerance: 'error', 'adjust' or 'ignore'
    character(len=8) :: initial_penetration = 'error'
    real(rk) :: search_margin = 0.0_rk !< territory margin (0 = automatic)
    integer :: search_every = 0 !< cycles between global searches (0 = automatic)
    integer :: sweeps = 1 !< DLM: Gauss-Seidel sweeps of the pair forces (1 = one pass)
    !> DLM velocity form: fraction of a facet pair's penetration at t^n
    !> removed over the step (Baumgarte-type position feedback; 0 = none;
    !> negative = not given in the deck: the default of contact_enforce)
    real(rk) :: recovery = -1.0_rk
    !> Coulomb friction coefficient (0: frictionless, the friction code is skipped)
    real(rk) :: friction = 0.0_rk
    !> DAM: a second pass with master and slave swapped (contact_enforce)
    logical :: symmetric = .true.
  end type contact_spec_t

  !> Geometry of one surface at x^n, computed once per cycle (in the
  !> predictor; both stages use x^n) and shared by every segment pair.
  type, public :: surface_geometry_t
    real(rk), allocatable :: facets(:, :, :, :) !< (3, 3, SEGMENT_FACET_COUNT, nseg)
    real(rk), allocatable :: normal(:, :, :) !< (3, SEGMENT_FACET_COUNT, nseg) facet unit normals
    real(rk), allocatable :: area(:, :) !< (SEGMENT_FACET_COUNT, nseg) facet areas
    real(rk), allocatable :: quad_normal(:, :) !< (3, nseg) segment unit normals
    real(rk), allocatable :: nodal_area(:) !< (ncn) dual-cell areas of the surface's nodes
  end type surface_geometry_t

  !> One contact pair (interface): method-neutral surfaces, pairs, geometry
  !> and diagnostics; the method's own state is in its object.
  type, public :: interface_t
    type(contact_spec_t), public :: spec
    !> the method (contact_factory); its rounds, search pair kind, own arrays
    class(contact_method_t), allocatable :: method
    logical :: self = .false.
    !> A reverse pass (a method's second pass with the sides swapped, DAM
    !> symmetric) is an interface of its own after the deck's (mirror_of:
    !> that deck interface; mirror: the deck interface's reverse pass). Its
    !> diagnostics go to the deck interface's columns (contact_monitor).
    integer :: mirror = 0, mirror_of = 0
    logical :: single_part = .false. !< every pair on part 0 (set by the method)
    type(contact_surface_t) :: all_a, all_b !< whole surfaces, contact index (b = master for DAM)
    type(contact_surface_t) :: a, b !< this part's local surfaces, local index
    real(rk) :: size = 0.0_rk !< median segment size of both surfaces
    real(rk) :: margin = 0.0_rk !< territory margin in use
    !> (2, n) this part's pairs, local numbers: PAIR_SEGMENTS (segment of a,
    !> segment of b), PAIR_NODE_SEGMENT (node, segment of b)
    integer, allocatable :: pairs(:, :)
    integer(i8), allocatable :: pair_key(:) !< PAIR_SEGMENTS: (n) global order of each pair
    integer, allocatable :: home_a(:), home_b(:) !< segments of all_a, all_b homed on this rank
    integer, allocatable :: home_a_node(:, :), home_b_node(:, :) !< (4, n) their local mesh nodes
    !> PAIR_NODE_SEGMENT: owned nodes of all_a (surface node index), the key nodes
    integer, allocatable :: own_slave(:)
    logical, allocatable :: was_active(:) !< (nown) owned node carried contact force last step
    type(surface_geometry_t) :: ga, gb !< geometry of a and b at x^n
    type(step_sums_t) :: sums !< this part's sums of the stage
    real(rk) :: pen_sq = 0.0_rk, pen_weight = 0.0_rk !< sums(pen_sq, weight) over the parts
    real(rk), public :: diag(CONTACT_DIAG_COUNT) = 0.0_rk !< last step's diagnostics
    ! Audit and per-interface output (contact_monitor).
    real(rk) :: reach = 0.0_rk !< audit reach: twice the larger median segment size
    !> (nown) initial penetration kept, per owned contact node (the audit,
    !> the restart); loffset: the same for the local set (ncn), from the
    !> owners with the migration plan (the methods read it)
    real(rk), allocatable :: offset(:), loffset(:)
    real(rk), allocatable :: sag_a(:), sag_b(:) !< faceting sagitta of all_a, all_b at t = 0
    real(rk), allocatable :: lsag_a(:), lsag_b(:) !< the same on the local surfaces a, b
    logical, allocatable :: own_in_a(:) !< (nown) owned node on surface a
    real(rk), allocatable :: fc_own(:, :) !< (3, nown) the interface's force (corrector)
    type(exact_sum_t) :: work_step !< this rank's terms of the interface's contact work, last step
    real(rk) :: work = 0.0_rk !< contact work of the interface so far (all ranks)
    integer(i8) :: warn_cycle = -1000000000_i8 !< cycle of the last audit warning (none yet)
    integer :: warn_skipped = 0 !< violations since that warning
  end type interface_t

  !> One interface's pairs from the global search, and the segments of the
  !> whole surfaces a part reads (during a rebuild).
  type, public :: selection_t
    integer, allocatable :: pairs(:, :) !< (2, n) DLM: segments a, b; DAM: node, segment
    !> the segments of the whole surfaces a, b in the local set, ascending
    integer, allocatable :: seg_a(:), seg_b(:)
  end type selection_t

  !> A list of integers (one per interface).
  type, public :: int_list_t
    integer, allocatable :: v(:)
  end type int_list_t

  !> All contact of a run.
  type, public :: contact_t
    integer :: npair = 0 !< interfaces: the deck's, then DAM's reverse passes
    integer :: ndeck = 0 !< the deck's interfaces
    !> (4, n) the deck's symmetry planes (unit normal, offset), for the audit
    real(rk), allocatable :: planes(:, :)
    type(interface_t), allocatable :: pairs(:)
    ! Every contact node (static, on every rank).
    integer :: nall = 0 !< contact nodes of all surfaces
    integer(i8), allocatable :: all_gid(:) !< (nall) global ids, ascending
    ! Owned contact nodes of this rank (owned_index finds one by contact index).
    integer :: nown = 0
    integer, allocatable :: own_contact(:) !< (nown) contact index, ascending
    integer, allocatable :: own_local(:) !< (nown) local mesh node index
    !> (nown) nodal masses (fixed), a rigid node's scaled by RIGID_MASS_FACTOR
    real(rk), allocatable :: own_mass(:)
    logical, allocatable :: own_rigid(:) !< (nown) motion prescribed (a velocity boundary)
    !> The owner directory: the mesh-owner rank of the contact nodes whose
    !> global id gid has mod(gid, nranks) = this rank (directory_rank), by
    !> ascending gid; a part asks it for the owners of its local set
    !> (contact_parts: owners_of). About nall / nranks entries per rank.
    integer(i8), allocatable :: dir_gid(:)
    integer, allocatable :: dir_owner(:)
    logical, allocatable :: key_capable(:) !< (nown) the node can key pairs (DLM first
                                           !< corner of an a-segment, DAM slave node)
    integer(i8), allocatable :: key_weight(:) !< (nown) RCB weight: pairs keyed at the last search
    real(rk), allocatable :: fc(:, :) !< (3, nown) contact force of the stage
    ! This rank's RCB part.
    integer :: ncn = 0 !< nodes of the local set
    integer, allocatable :: all_of(:) !< (ncn) their contact index, ascending
    real(rk), allocatable :: mass(:) !< (ncn) from the owners' own_mass
    logical, allocatable :: rigid(:) !< (ncn) from the owners' own_rigid
    integer, allocatable :: owner(:) !< (ncn) mesh-owner rank of each
    !> (ncn) the place of each among the nodes its owner sends this part
    !> (from 1; the records name their nodes by it: contact_records)
    integer, allocatable :: owner_pos(:)
    real(rk), allocatable :: x(:, :), v(:, :), f(:, :) !< (3, ncn) x^n, v^n, f of the stage
    ! Migration plan (rebuilt with the RCB).
    integer, allocatable :: recv_count(:) !< (nranks) local nodes sent by each owner
    integer, allocatable :: recv_local(:) !< (ncn) local node of each, by owner
    integer, allocatable :: send_count(:) !< (nranks) owned nodes sent to each part
    integer, allocatable :: send_own(:) !< owned index of each, by part
    integer(i8) :: next_search = 0 !< cycle of the next global search and RCB
    !> a restart's schedule: the uninterrupted run's next search (the
    !> restart's first stage searches anyway, without an audit before it)
    integer(i8) :: resumed_search = -1
    real(rk) :: speed = 0.0_rk !< largest contact node speed at t^n (all ranks)
    !> the cycle whose t^n gave speed and the local set's x, v (the
    !> corrector reuses them: only the forces are new)
    integer(i8) :: speed_cycle = -1, gathered_cycle = -1
    !> The cycle's step over its stable step (< 1 when the step is cut short
    !> to land on a dump time or t_end): DLM's recovery speed is taken over
    !> the stable step, so a short landing step does not fling nodes apart.
    real(rk) :: landing = 1.0_rk
    integer :: rebuilds = 0 !< global searches (RCB rebuilds) so far
    integer(i8) :: impact_cycles = 0 !< cycles whose step the impact limit shortened
    integer :: recuts = 0 !< searches whose RCB was cut again (load drift)
    integer :: balanced_searches = 0 !< searches that found pairs
    real(rk) :: balance_sum = 0.0_rk !< sum over them of largest part's pairs / mean
    real(rk) :: balance_worst = 0.0_rk !< the largest of these ratios
    integer :: ncn_max = 0 !< largest local set of this rank so far
    real(rk) :: search_seconds = 0.0_rk, enforce_seconds = 0.0_rk, migrate_seconds = 0.0_rk
    !> time in the first collective of each call: waiting for the slowest rank's
    !> hydro (load imbalance), kept out of the contact times
    real(rk) :: wait_seconds = 0.0_rk
    !> the contact's communication (search, migration, diagnostics; not the
    !> audit): bytes, messages, exchanges and collectives of this rank
    type(traffic_t) :: traffic
    integer(i8) :: cycles = 0 !< corrector stages run (cycles), for the per-cycle figures
    ! The audit (contact_monitor).
    real(rk), allocatable :: gap_own(:) !< (nown) smallest signed gap of each owned node
    logical :: audit_due = .true. !< a search ran since the last audit
    logical :: refreshed = .false. !< the surfaces were rebuilt in this run
    integer(i8) :: audited_cycle = -1 !< cycle of the last audit
    logical :: stop_run = .false. !< on_penetration = 'stop' and the audit failed
    real(rk) :: audit_seconds = 0.0_rk !< wall time in the audit (set by the caller)
    integer :: audits = 0 !< audits run
    !> the largest segment span (longest distance between two corners of a
    !> segment) of the contact surfaces at the last audit: the next audit's
    !> first guess of how far around its owned nodes a rank needs positions
    !> (contact_monitor: near_nodes; 0 = none yet)
    real(rk) :: audit_span = 0.0_rk
    ! Contact output (dumps, history, restart; each interface's work is in pairs(:)%work).
    !> (nnode local) signed distance of a contact node to the opposite surface
    !> at the last audit (< 0: penetration; 0 off the contact surfaces)
    real(rk), allocatable :: node_gap(:)
    real(rk) :: work = 0.0_rk !< work of the contact forces so far (all ranks)
  end type contact_t

  !> A contact method: what DAM and DLM (and any other) do differently.
  !> contact_enforce runs a stage as rounds: in round r each RCB part runs
  !> part_round on its pairs and writes records (record_width(r) values
  !> each) for the owners of the nodes; the owners run owner_round on what
  !> arrived, in key order, and either hand back per-node values
  !> (owner_width(r) each) that go to the parts for round r + 1, or, in the
  !> last round, the contact force of each owned node. contact_parts asks
  !> pair_kind for the search and the RCB keys. A method holds its own
  !> arrays (the cycle's geometry caches, the owners' values between rounds).
  type, abstract, public :: contact_method_t
    !> record buffers of the rounds, kept from stage to stage
    type(records_t) :: kept(MAX_ROUNDS)
  contains
    !> PAIR_SEGMENTS or PAIR_NODE_SEGMENT
    procedure(method_integer), deferred, nopass :: pair_kind
    !> rounds of a stage (1..MAX_ROUNDS)
    procedure(method_integer), deferred, nopass :: rounds
    !> values per record of round r, from the parts to the owners
    procedure(method_width), deferred, nopass :: record_width
    !> values per owned node after round r (< rounds()), back to the parts
    procedure(method_width), deferred, nopass :: owner_width
    !> settings from the deck group; reverse: the interface is a reverse pass
    procedure(method_configure), deferred :: configure
    !> the deck's surfaces a and b as this method's sides a and b
    procedure(method_sides), deferred, nopass :: sides
    !> the interface gets a reverse pass (sides swapped) after the deck's
    procedure(method_flag), deferred :: reverse_pass
    !> the method enforces the nodes of surface b too (the audit's unheld)
    procedure(method_flag), deferred :: enforces_b
    !> a rebuilt pair list arrived on this part: forget the cycle's caches
    procedure(method_localized), deferred :: localized
    !> the parts' round r (geometry at x^n in round 1 of the predictor)
    procedure(method_part_round), deferred :: part_round
    !> the owners' round r: values for the parts, or (last round) forces
    procedure(method_owner_round), deferred :: owner_round
    !> RMS penetration of the step from the summed squares and weights
    procedure(method_rms), deferred, nopass :: pen_rms
    !> bytes of the method's working arrays on this part (contact_report)
    procedure(method_bytes), deferred :: bytes
  end type contact_method_t

  !> A method in a list (before its interface exists).
  type, public :: method_slot_t
    class(contact_method_t), allocatable :: method
  end type method_slot_t

  abstract interface
    pure integer function method_integer()
    end function method_integer

    pure integer function method_width(r)
      integer, intent(in) :: r
    end function method_width

    pure logical function method_flag(this)
      import :: contact_method_t
      class(contact_method_t), intent(in) :: this
    end function method_flag

    subroutine method_configure(this, spec, reverse, single_part)
      import :: contact_method_t, contact_spec_t
      class(contact_method_t), intent(inout) :: this
      type(contact_spec_t), intent(in) :: spec
      logical, intent(in) :: reverse
      logical, intent(out) :: single_part !< every pair of the interface on part 0
    end subroutine method_configure

    pure subroutine method_sides(spec, side_a, side_b)
      import :: contact_spec_t, SURFACE_LEN
      type(contact_spec_t), intent(in) :: spec
      character(len=SURFACE_LEN), intent(out) :: side_a, side_b
    end subroutine method_sides

    subroutine method_localized(this, ct, p)
      import :: contact_method_t, contact_t, interface_t
      class(contact_method_t), intent(inout) :: this
      type(contact_t), intent(in) :: ct
      type(interface_t), intent(inout) :: p
    end subroutine method_localized

    subroutine method_part_round(this, ct, p, k, r, dt, final, inflow, out)
      import :: contact_method_t, contact_t, interface_t, records_t, rk
      class(contact_method_t), intent(inout) :: this
      type(contact_t), intent(in) :: ct
      type(interface_t), intent(inout) :: p
      integer, intent(in) :: k, r !< the interface's number, the round
      real(rk), intent(in) :: dt !< the stage's step
      logical, intent(in) :: final !< the corrector (geometry cached by the predictor)
      !> (owner_width(r - 1), ncn) the owners' values of the last round (r > 1)
      real(rk), intent(in) :: inflow(:, :)
      type(records_t), intent(inout) :: out
    end subroutine method_part_round

    subroutine method_owner_round(this, ct, p, r, rec, v_old, force, dt, values, fc, has)
      import :: contact_method_t, contact_t, interface_t, records_t, rk
      class(contact_method_t), intent(inout) :: this
      type(contact_t), intent(in) :: ct
      type(interface_t), intent(inout) :: p
      integer, intent(in) :: r !< the round
      type(records_t), intent(in) :: rec !< the records of the owned nodes, key order
      real(rk), intent(in) :: v_old(:, :), force(:, :), dt
      !> (owner_width(r), nown) values for the parts (rounds before the last)
      real(rk), intent(out) :: values(:, :)
      real(rk), intent(inout) :: fc(:, :) !< (3, nown) the interface's force (last round)
      logical, intent(inout) :: has(:) !< (nown) the node carries a force (last round)
    end subroutine method_owner_round

    pure real(rk) function method_rms(pen_sq, weight)
      import :: rk
      real(rk), intent(in) :: pen_sq, weight
    end function method_rms

    pure real(rk) function method_bytes(this)
      import :: contact_method_t, rk
      class(contact_method_t), intent(in) :: this
    end function method_bytes
  end interface

  !> Initial penetration kept as an offset, per node of surfaces a and b
  !> (surface node order), from the set-up audit.
  type, public :: initial_offsets_t
    real(rk), allocatable :: a(:), b(:)
  end type initial_offsets_t


contains

  !> Penetration a pair keeps without recovery: ALLOWANCE_SHARE of the deck's
  !> penetration_tolerance, or (automatic) of the audit's tolerance: the
  !> larger of SIZE_ALLOWANCE x the smaller side's size and
  !> ALLOWANCE_SHARE x the faceting sagitta (the mismatch of two faceted
  !> versions of one curved surface, left alone; docs/contact.md, 9.3).
  pure real(rk) function recovery_allowance(tolerance, area_a, area_b, sagitta)
    real(rk), intent(in) :: tolerance !< the deck's (0 = automatic)
    real(rk), intent(in) :: area_a, area_b !< the two sides' areas
    real(rk), intent(in) :: sagitta !< the larger faceting sagitta of the two
    if (tolerance > 0.0_rk) then
      recovery_allowance = ALLOWANCE_SHARE * tolerance
    else
      recovery_allowance = max(SIZE_ALLOWANCE * sqrt(min(area_a, area_b)), &
          ALLOWANCE_SHARE * sagitta)
    end if
  end function recovery_allowance

  !> The penetration a pair's recovery puts back: its depth beyond the kept
  !> offset and the allowance (zero within), and no more than the excess of
  !> a pair at the audit's tolerance (allowance / ALLOWANCE_SHARE). The
  !> recovery corrects the drift a step leaves, which is within the
  !> tolerance; a pair found deeper is a geometric event, not drift (a node
  !> wrapped by a fold of the other surface, faces of a crushed zone), and
  !> put back in proportion to its depth it takes kinetic energy in
  !> proportion to the depth squared, and more where the push cannot
  !> succeed: a mushroomed rod's rim node held by target facets facing it
  !> from both sides was pushed out of both at 1 km/s every other step, the
  !> pairs' approach speeds grew 1.4 times a step, and the contact did
  !> +130 J of work in 10 cycles (problems/penetration at 2166 m/s; docs/
  !> contact.md 9.3). Beyond the tolerance a pair is held (its approach
  !> stopped) and put back at the tolerance's rate.
  pure real(rk) function recovery_excess(depth, allowance)
    real(rk), intent(in) :: depth !< penetration beyond the kept offset
    real(rk), intent(in) :: allowance !< recovery_allowance of the pair
    recovery_excess = max(min(depth - allowance, &
        (1.0_rk / ALLOWANCE_SHARE - 1.0_rk) * allowance), 0.0_rk)
  end function recovery_excess

  !> The recovery's separating speed for a penetration excess over a step
  !> dt (the fraction `fraction` of it put back over the stable step: dt /
  !> landing), at most RECOVERY_SPEED_SHARE of the contact's largest node
  !> speed: a put-back is never faster than the fastest contact node moves.
  !> The recovery is meant for the drift a step leaves, and a fraction per
  !> step is a speed of fraction x excess / dt: where a pair is found deep,
  !> or the step is set far below the contact's own time scale (a crushed
  !> zone elsewhere), that speed is many times the motion's, and the
  !> put-back puts kinetic energy into the run (a penetration run put a
  !> 2.6 mm pair back at 70 km/s and gained 5e3 J in 20 cycles). A deck
  !> whose steps are far below its contact's time scale also lowers the
  !> fraction (&contact recovery; problems/penetration).
  pure real(rk) function recovery_speed_of(fraction, excess, landing, dt, speed) result(v)
    real(rk), intent(in) :: fraction !< share of the excess put back over dt
    real(rk), intent(in) :: excess !< recovery_excess of the pair
    real(rk), intent(in) :: landing !< the step's share of the stable step (ct%landing)
    real(rk), intent(in) :: dt !< the step the fraction is put back over
    real(rk), intent(in) :: speed !< the contact's largest node speed (ct%speed)
    v = min(fraction * excess * landing / dt, RECOVERY_SPEED_SHARE * speed)
  end function recovery_speed_of

  !> A surface's facets, facet normals and areas, segment normals and nodal
  !> areas at x (once per cycle; every segment pair then reads them).
  subroutine geometry_update(x, surf, g)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    type(surface_geometry_t), intent(inout) :: g
    integer :: s, i
    if (.not. allocated(g%facets)) allocate(g%facets(3, 3, SEGMENT_FACET_COUNT, surf%nseg), &
        g%normal(3, SEGMENT_FACET_COUNT, surf%nseg), g%area(SEGMENT_FACET_COUNT, surf%nseg), &
        g%quad_normal(3, surf%nseg), g%nodal_area(size(x, 2)))
    do s = 1, surf%nseg
      call segment_facets(x(:, surf%segments(:, s)), g%facets(:, :, :, s))
      do i = 1, SEGMENT_FACET_COUNT
        g%normal(:, i, s) = triangle_unit_normal(g%facets(:, :, i, s))
        g%area(i, s) = norm2(triangle_vector_area(g%facets(:, :, i, s)))
      end do
      g%quad_normal(:, s) = quad_unit_normal(x(:, surf%segments(:, s)))
    end do
    g%nodal_area = 0.0_rk
    call nodal_areas(x, surf, g%nodal_area)
  end subroutine geometry_update

  !> Capture tolerance: the deck's, or twice the closing distance of one step.
  pure real(rk) function capture_of(p, speed, dt) result(capture)
    type(interface_t), intent(in) :: p
    real(rk), intent(in) :: speed, dt
    capture = p%spec%capture
    if (.not. capture > 0.0_rk) capture = max(2.0_rk * speed * dt, 1.0e-3_rk * p%size)
  end function capture_of


  !> The contact node that decides the part of a pair: a segment pair, the
  !> first corner of its a-segment; a node-segment pair, its node.
  pure integer function key_node(p, pair) result(c)
    type(interface_t), intent(in) :: p
    integer, intent(in) :: pair(2)
    if (p%method%pair_kind() == PAIR_SEGMENTS) then
      c = p%all_a%segments(1, pair(1))
    else
      c = pair(1)
    end if
  end function key_node


  !> Owned index of contact node c on this rank (a binary search of the
  !> ascending own_contact), 0 if this rank does not own it.
  pure integer function owned_index(ct, c) result(i)
    type(contact_t), intent(in) :: ct
    integer, intent(in) :: c !< contact index
    i = sorted_find(ct%own_contact, c)
  end function owned_index

  !> Forget a surface's cached geometry (its size changes with the local set).
  subroutine geometry_free(g)
    type(surface_geometry_t), intent(inout) :: g
    if (allocated(g%facets)) deallocate(g%facets, g%normal, g%area, g%quad_normal, g%nodal_area)
  end subroutine geometry_free


end module contact_state
