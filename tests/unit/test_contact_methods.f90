!> A third contact method needs no change to the contact driver: a
!> do-nothing method (null_t), registered here and only here with the
!> factory, runs through set-up, the search on the RCB parts, its two
!> rounds at the parts and the owners (with per-node values sent back to
!> the parts between them), the diagnostics and the audit of a real deck.
!> Checks, on every rank count:
!> * the stage's forces come back unchanged, bit for bit, and no node
!>   carries a contact force;
!> * each round ran once per stage on every part and at every owner;
!> * the owners' values of round 1 reach the parts' round 2 for exactly
!>   the nodes of each local set (each local node receives its own global
!>   id), and every record sent reached the owner of its node (the owners'
!>   count of records equals the parts' count over the ranks);
!> * the diagnostics are zero.
!> Usage: test_contact_methods DECK (a deck with one &contact; its method is
!> replaced by 'none').
module null_method
  use core_kinds, only: rk, i8
  use contact_records, only: records_t, add_record
  use contact_state, only: contact_method_t, contact_t, interface_t, contact_spec_t, &
      PAIR_SEGMENTS, SURFACE_LEN
  implicit none
  private
  public :: make_null

  !> Does nothing but count and check what the driver hands it.
  type, extends(contact_method_t), public :: null_t
    integer :: part_calls(2) = 0, owner_calls(2) = 0
    integer :: records_sent = 0, records_received = 0
    integer :: inflow_checked = 0, inflow_wrong = 0
  contains
    procedure, nopass :: pair_kind => null_pair_kind
    procedure, nopass :: rounds => null_rounds
    procedure, nopass :: record_width => null_record_width
    procedure, nopass :: owner_width => null_owner_width
    procedure :: configure => null_configure
    procedure, nopass :: sides => null_sides
    procedure :: reverse_pass => null_flag
    procedure :: enforces_b => null_flag
    procedure :: localized => null_localized
    procedure :: part_round => null_part_round
    procedure :: owner_round => null_owner_round
    procedure, nopass :: pen_rms => null_pen_rms
    procedure :: bytes => null_bytes
  end type null_t

contains

  subroutine make_null(method)
    class(contact_method_t), allocatable, intent(out) :: method
    allocate(null_t :: method)
  end subroutine make_null

  pure integer function null_pair_kind()
    null_pair_kind = PAIR_SEGMENTS
  end function null_pair_kind

  pure integer function null_rounds()
    null_rounds = 2
  end function null_rounds

  pure integer function null_record_width(r)
    integer, intent(in) :: r
    null_record_width = r
  end function null_record_width

  !> Round 1 sends each owned node's global id back to the parts.
  pure integer function null_owner_width(r)
    integer, intent(in) :: r
    null_owner_width = merge(1, 0, r == 1)
  end function null_owner_width

  subroutine null_configure(this, spec, reverse, single_part)
    class(null_t), intent(inout) :: this
    type(contact_spec_t), intent(in) :: spec
    logical, intent(in) :: reverse
    logical, intent(out) :: single_part
    single_part = .false.
    if (reverse .or. len_trim(spec%name) < 0) this%part_calls = -1
  end subroutine null_configure

  pure subroutine null_sides(spec, side_a, side_b)
    type(contact_spec_t), intent(in) :: spec
    character(len=SURFACE_LEN), intent(out) :: side_a, side_b
    side_a = spec%surface_a
    side_b = spec%surface_b
  end subroutine null_sides

  pure logical function null_flag(this)
    class(null_t), intent(in) :: this
    null_flag = this%part_calls(1) < 0
  end function null_flag

  subroutine null_localized(this, ct, p)
    class(null_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    if (ct%ncn < 0 .or. p%self) this%inflow_wrong = this%inflow_wrong + 1
  end subroutine null_localized

  !> Round 1: one record per node of the local set (value 1); round 2:
  !> check the owners' values.
  subroutine null_part_round(this, ct, p, k, r, dt, final, inflow, out)
    class(null_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: k, r
    real(rk), intent(in) :: dt
    logical, intent(in) :: final
    real(rk), intent(in) :: inflow(:, :)
    type(records_t), intent(inout) :: out
    integer :: l
    this%part_calls(r) = this%part_calls(r) + 1
    if (.not. dt > 0.0_rk .or. (final .and. .not. allocated(p%pairs))) &
        this%inflow_wrong = this%inflow_wrong + 1
    if (r == 1) then
      do l = 1, ct%ncn
        call add_record(out, l, k, int(ct%all_of(l), i8), [1.0_rk])
        this%records_sent = this%records_sent + 1
      end do
    else
      if (size(inflow, 2) /= ct%ncn) this%inflow_wrong = this%inflow_wrong + 1
      do l = 1, min(ct%ncn, size(inflow, 2))
        this%inflow_checked = this%inflow_checked + 1
        if (inflow(1, l) /= real(ct%all_gid(ct%all_of(l)), rk)) &
            this%inflow_wrong = this%inflow_wrong + 1
      end do
    end if
  end subroutine null_part_round

  subroutine null_owner_round(this, ct, p, r, rec, v_old, force, dt, values, fc, has)
    class(null_t), intent(inout) :: this
    type(contact_t), intent(in) :: ct
    type(interface_t), intent(inout) :: p
    integer, intent(in) :: r
    type(records_t), intent(in) :: rec
    real(rk), intent(in) :: v_old(:, :), force(:, :), dt
    real(rk), intent(out) :: values(:, :)
    real(rk), intent(inout) :: fc(:, :)
    logical, intent(inout) :: has(:)
    integer :: i
    this%owner_calls(r) = this%owner_calls(r) + 1
    this%records_received = this%records_received + rec%n
    if (r == 1) then
      do i = 1, ct%nown
        values(1, i) = real(ct%all_gid(ct%own_contact(i)), rk)
      end do
    end if
    if (size(fc, 2) /= ct%nown .or. size(has) /= ct%nown .or. .not. dt > 0.0_rk .or. &
        size(v_old, 2) /= size(force, 2) .or. p%mirror /= 0) &
        this%inflow_wrong = this%inflow_wrong + 1
  end subroutine null_owner_round

  pure real(rk) function null_pen_rms(pen_sq, weight)
    real(rk), intent(in) :: pen_sq, weight
    null_pen_rms = pen_sq * weight
  end function null_pen_rms

  pure real(rk) function null_bytes(this)
    class(null_t), intent(in) :: this
    null_bytes = real(this%records_sent, rk)
  end function null_bytes

end module null_method


program test_contact_methods
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: timers_t, wall_time
  use parallel_env, only: par_init, par_finalize, par_sum, par_rank
  use io_h5, only: h5_library_open
  use io_deck, only: config_t, deck_read
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_boundary, only: boundary_t
  use hydro_driver, only: material_zones_t
  use io_probe, only: probes_t
  use contact_enforce, only: contact_t, contact_apply
  use contact_factory, only: contact_method_register
  use contact_monitor, only: contact_audit_run, contact_step_end
  use app_setup, only: setup_run
  use null_method, only: null_t, make_null
  use check, only: check_true, check_summary
  implicit none
  character(len=512) :: deck
  type(config_t) :: config
  type(status_t) :: status
  type(mesh_t) :: mesh
  type(boundary_t) :: bc
  type(state_t) :: state
  type(material_zones_t) :: mz
  type(contact_t) :: ct
  type(probes_t) :: probes
  type(timers_t) :: timers
  real(rk), allocatable :: force(:, :), before(:, :)
  character(len=400) :: msg
  integer :: ierr, cycle, stage, sent, received, wrong, checked
  logical :: same

  call par_init()
  call get_command_argument(1, deck)
  call h5_library_open(ierr, msg)
  call deck_read(trim(deck), config, status)
  call check_true('deck read', status%ok())
  config%contacts(:)%method = 'none'
  call contact_method_register('none', make_null)
  call timers%add('restart read')
  call setup_run(config, '', .false., mesh, bc, state, mz, ct, probes, timers, status)
  call check_true('set-up with the registered method', status%ok())
  call check_true('one interface per deck group', ct%npair == size(config%contacts))

  ! A few cycles of stages on a hydro-like force field (position-dependent,
  ! so nothing cancels by accident).
  allocate(force(3, size(state%node_position, 2)))
  same = .true.
  do cycle = 1, 4
    do stage = 1, 2
      force = sin(state%node_position * real(cycle + stage, rk))
      before = force
      call contact_apply(ct, state%node_position, state%node_velocity, force, &
          1.0e-3_rk, int(cycle, i8), stage == 2, wall_time)
      same = same .and. all(force == before) .and. all(ct%fc == 0.0_rk)
    end do
    call contact_step_end(ct, 0.0_rk)
  end do
  call contact_audit_run(ct, state%node_position, 4_i8, 0.0_rk)
  call check_true('forces unchanged bit for bit, no contact force', &
      par_sum(merge(0, 1, same)) == 0)
  select type (m => ct%pairs(1)%method)
  type is (null_t)
    call check_true('each round once per stage on every part and owner', &
        par_sum(merge(0, 1, all(m%part_calls == 8) .and. all(m%owner_calls == 8))) == 0)
    sent = par_sum(m%records_sent)
    received = par_sum(m%records_received)
    call check_true('every record reached its owner', sent > 0 .and. sent == received)
    wrong = par_sum(m%inflow_wrong)
    checked = par_sum(m%inflow_checked)
    call check_true('round 1 values reach the parts'' round 2 for each local node', &
        wrong == 0 .and. checked > 0)
    if (par_rank() == 0) write(output_unit, '(a,i0,a,i0)') 'records ', sent, &
        ', local nodes checked ', checked
  class default
    call check_true('the interface holds the registered method', .false.)
  end select
  call check_true('diagnostics zero', all(ct%pairs(1)%diag(1:8) == 0.0_rk))
  call par_finalize()
  call check_summary()
end program test_contact_methods
