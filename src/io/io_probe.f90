!> Time-history probes (&probe): chosen fields at one node and/or the zone
!> that holds it, written by rank 0 to <output directory>/probe_<name>.csv.
!> The node (or zone) is fixed at set-up on the deck's mesh, so it is the same
!> material point for the whole run and after any restart. The rank that owns
!> the node (zone) gives its values; an all-gather brings them to rank 0
!> unchanged, so the files do not depend on the rank count.
module io_probe
  use, intrinsic :: iso_fortran_env, only: error_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_units, only: unit_of
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use parallel_env, only: par_rank, par_size, par_max, par_allgather
  use parallel_route, only: par_min_i8, par_max_i8
  use io_config, only: probe_spec_t, PROBE_FIELD_LEN
  implicit none
  private
  public :: probe_setup, probe_open, probe_sample

  !> One probe, resolved on the mesh.
  type :: probe_t
    character(len=:), allocatable :: path !< the CSV file
    character(len=:), allocatable :: header !< its first line
    character(len=PROBE_FIELD_LEN), allocatable :: fields(:)
    integer(i8) :: node_gid = 0 !< global node id of the nodal fields
    integer(i8) :: zone_gid = 0 !< global zone id of the zone fields
    integer :: node_local = 0 !< owned local index of that node on this rank (0: not here)
    integer :: zone_local = 0 !< owned local index of that zone on this rank (0: not here)
    integer :: node_rank = 0 !< owner rank of the node
    integer :: zone_rank = 0 !< owner rank of the zone
    integer :: nvalue = 0 !< values per row (after cycle and time)
    logical, allocatable :: nodal(:) !< (nvalue) value comes from the node
    integer :: every = 0
    real(rk) :: interval = 0.0_rk
  end type probe_t

  !> Every probe of the run.
  type, public :: probes_t
    type(probe_t), allocatable :: p(:)
    real(rk) :: time_last = 0.0_rk !< simulated time at the previous look
  end type probes_t

contains

  !> Resolve every &probe on the deck's (global) mesh: node range, the zone
  !> that holds a point, owner ranks, columns. Problems go to status, naming
  !> the probe and the key.
  subroutine probe_setup(specs, mesh, coordinates, directory, units, probes, status)
    type(probe_spec_t), intent(in) :: specs(:)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: coordinates(:, :) !< (3, mesh%nnode) initial positions
    character(len=*), intent(in) :: directory !< &output directory
    character(len=*), intent(in) :: units !< &control units
    type(probes_t), intent(out) :: probes
    type(status_t), intent(inout) :: status
    integer :: i, z, k, n, f
    integer(i8) :: zg
    character(len=:), allocatable :: where
    character(len=64) :: text
    real(rk) :: best, d

    allocate(probes%p(size(specs)))
    do i = 1, size(specs)
      associate(s => specs(i), p => probes%p(i))
        where = '&probe '''//trim(s%name)//''''
        if (s%at_point) then
          ! The lowest-id zone holding the point, over every rank's owned zones.
          z = containing_zone(mesh, coordinates, s%point)
          zg = huge(1_i8)
          if (z > 0) zg = mesh%zone_gid(z)
          zg = par_min_i8(zg)
          if (zg == huge(1_i8)) then
            write(text, '(3(es12.5,:,", "))') s%point
            call status%add(where//': point: ('//trim(text)//') is outside the mesh')
            cycle
          end if
          ! The nearest corner of that zone (ties: the lowest id), by its owner.
          p%node_gid = 0
          if (z > 0) then
            if (mesh%zone_gid(z) == zg) then
              best = huge(1.0_rk)
              do k = 1, 8
                n = mesh%zone_node(k, z)
                d = sum((coordinates(:, n) - s%point)**2)
                if (d < best .or. (d == best .and. mesh%node_gid(n) < p%node_gid)) then
                  best = d
                  p%node_gid = mesh%node_gid(n)
                end if
              end do
            end if
          end if
          p%node_gid = par_max_i8(p%node_gid)
          p%zone_gid = zg
        else
          if (s%node < 1 .or. s%node > mesh%nnode_global) then
            write(text, '(i0,a,i0,a)') s%node, ' is out of range (the mesh has nodes 1 to ', &
                mesh%nnode_global, ')'
            call status%add(where//': node: '//trim(text))
            cycle
          end if
          p%node_gid = s%node
          ! Zone fields of a node probe: the node's lowest-id zone (the first
          ! of its owner's corner list, which is sorted by zone id).
          zg = 0
          do n = 1, mesh%nnode_owned
            if (mesh%node_gid(n) == s%node) zg = mesh%zone_gid((mesh%corner_list( &
                mesh%corner_start(n)) - 1) / 8 + 1)
          end do
          p%zone_gid = par_max_i8(zg)
        end if
        do n = 1, mesh%nnode_owned
          if (mesh%node_gid(n) == p%node_gid) p%node_local = n
        end do
        do z = 1, mesh%nzone_owned
          if (mesh%zone_gid(z) == p%zone_gid) p%zone_local = z
        end do
        p%node_rank = par_max(merge(par_rank(), -1, p%node_local > 0))
        p%zone_rank = par_max(merge(par_rank(), -1, p%zone_local > 0))
        p%fields = s%fields
        p%every = s%every
        p%interval = s%interval
        p%path = trim(directory)//'/probe_'//trim(s%name)//'.csv'
        p%header = 'cycle,time ['//unit_of(units, 'time')//']'
        allocate(p%nodal(0))
        do f = 1, size(p%fields)
          select case (trim(p%fields(f)))
          case ('velocity')
            call column('velocity_x', 'velocity', .true.)
            call column('velocity_y', 'velocity', .true.)
            call column('velocity_z', 'velocity', .true.)
          case ('position')
            call column('position_x', 'length', .true.)
            call column('position_y', 'length', .true.)
            call column('position_z', 'length', .true.)
          case ('pressure')
            call column('pressure', 'pressure', .false.)
          case ('density')
            call column('density', 'density', .false.)
          case ('energy')
            call column('specific_internal_energy', 'specific_energy', .false.)
          case ('stress')
            call column('deviatoric_stress_xx', 'pressure', .false.)
            call column('deviatoric_stress_yy', 'pressure', .false.)
            call column('deviatoric_stress_zz', 'pressure', .false.)
            call column('deviatoric_stress_xy', 'pressure', .false.)
            call column('deviatoric_stress_yz', 'pressure', .false.)
            call column('deviatoric_stress_zx', 'pressure', .false.)
          case ('plastic_strain')
            call column('plastic_strain', 'dimensionless', .false.)
          case ('viscosity')
            call column('viscosity', 'pressure', .false.)
          case ('sound_speed')
            call column('sound_speed', 'velocity', .false.)
          end select
        end do
        p%nvalue = size(p%nodal)
      end associate
    end do

  contains

    subroutine column(name, quantity, nodal)
      character(len=*), intent(in) :: name, quantity
      logical, intent(in) :: nodal
      probes%p(i)%header = probes%p(i)%header//','//name//' ['//unit_of(units, quantity)//']'
      probes%p(i)%nodal = [probes%p(i)%nodal, nodal]
    end subroutine column

  end subroutine probe_setup

  !> The lowest-id owned zone of this rank that holds point x (each hex split
  !> into six tetrahedra about its 1-7 diagonal, exact for planar faces; a
  !> point on a face, within 1e-9 of the zone's volume, counts as inside);
  !> 0 when none does.
  integer function containing_zone(mesh, coordinates, x) result(zone)
    type(mesh_t), intent(in) :: mesh
    real(rk), intent(in) :: coordinates(:, :)
    real(rk), intent(in) :: x(3)
    integer, parameter :: TETS(3, 6) = reshape([2, 3, 7, 3, 4, 7, 4, 8, 7, 8, 5, 7, 5, 6, 7, &
        6, 2, 7], [3, 6])
    real(rk) :: c(3, 8), lo(3), hi(3), tol, v, a, b, w, e
    integer :: z, t, k
    zone = 0
    ! Owned zones are sorted by global id: the first that holds x is the lowest.
    do z = 1, mesh%nzone_owned
      do k = 1, 8
        c(:, k) = coordinates(:, mesh%zone_node(k, z))
      end do
      lo = minval(c, dim=2)
      hi = maxval(c, dim=2)
      tol = 1.0e-9_rk * maxval(hi - lo)
      if (any(x < lo - tol) .or. any(x > hi + tol)) cycle
      do t = 1, 6
        associate(p0 => c(:, 1), p1 => c(:, TETS(1, t)), p2 => c(:, TETS(2, t)), &
            p3 => c(:, TETS(3, t)))
          v = det(p1 - p0, p2 - p0, p3 - p0)
          if (v == 0.0_rk) cycle
          e = -1.0e-9_rk * abs(v)
          ! Barycentric volumes, each with the sign of v when x is inside.
          a = det(x - p0, p2 - p0, p3 - p0) * sign(1.0_rk, v)
          b = det(p1 - p0, x - p0, p3 - p0) * sign(1.0_rk, v)
          w = det(p1 - p0, p2 - p0, x - p0) * sign(1.0_rk, v)
          if (a >= e .and. b >= e .and. w >= e .and. abs(v) - a - b - w >= e) then
            zone = z
            return
          end if
        end associate
      end do
    end do
  end function containing_zone

  pure real(rk) function det(a, b, c)
    real(rk), intent(in) :: a(3), b(3), c(3)
    det = a(1) * (b(2) * c(3) - b(3) * c(2)) - a(2) * (b(1) * c(3) - b(3) * c(1)) &
        + a(3) * (b(1) * c(2) - b(2) * c(1))
  end function det

  !> Rank 0 starts every probe file: the header line, and on a restart the
  !> rows of the earlier run up to the restart cycle (when the header is the
  !> same; otherwise the file starts again).
  subroutine probe_open(probes, state, restarted)
    type(probes_t), intent(inout) :: probes
    type(state_t), intent(in) :: state
    logical, intent(in) :: restarted
    integer :: i, unit, ios, n, comma
    integer(i8) :: c
    logical :: exists, same
    character(len=8192) :: line
    character(len=8192), allocatable :: keep(:)
    probes%time_last = state%time
    if (par_rank() /= 0) return
    do i = 1, size(probes%p)
      associate(p => probes%p(i))
        allocate(keep(0))
        inquire(file=p%path, exist=exists)
        if (restarted .and. exists) then
          open(newunit=unit, file=p%path, status='old', action='read')
          read(unit, '(a)', iostat=ios) line
          same = ios == 0 .and. trim(line) == p%header
          do while (same)
            read(unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            comma = index(line, ',')
            if (comma < 2) cycle
            read(line(1:comma - 1), *, iostat=ios) c
            if (ios == 0 .and. c <= state%cycle) keep = [character(len=len(line)) :: keep, line]
          end do
          close(unit)
          if (.not. same) write(error_unit, '(a)') 'warning: '//p%path//': its columns differ '// &
              'from this deck''s &probe; the file starts again'
        end if
        open(newunit=unit, file=p%path, status='replace', action='write')
        write(unit, '(a)') p%header
        do n = 1, size(keep)
          write(unit, '(a)') trim(keep(n))
        end do
        close(unit)
        deallocate(keep)
      end associate
    end do
  end subroutine probe_open

  !> After a cycle (and at cycle 0): every probe that is due writes a row.
  !> Due: cycle 0; with every, cycles that are multiples of it; with
  !> interval, the first cycle at or past each multiple of it (steps do not
  !> land on probe times; the row has the cycle's own time).
  subroutine probe_sample(probes, state)
    type(probes_t), intent(inout) :: probes
    type(state_t), intent(in) :: state
    logical, allocatable :: due(:)
    real(rk), allocatable :: record(:), all(:, :)
    integer :: i, j, k, total, unit
    character(len=32) :: word
    character(len=:), allocatable :: row

    if (size(probes%p) == 0) return
    allocate(due(size(probes%p)))
    do i = 1, size(probes%p)
      associate(p => probes%p(i))
        if (state%cycle == 0) then
          due(i) = .true.
        else if (p%every > 0) then
          due(i) = mod(state%cycle, int(p%every, i8)) == 0
        else
          due(i) = floor(state%time / p%interval) > floor(probes%time_last / p%interval)
        end if
      end associate
    end do
    probes%time_last = state%time
    if (.not. any(due)) return
    total = sum(probes%p%nvalue, mask=due)
    allocate(record(total), all(total, par_size()))
    record = 0.0_rk
    k = 0
    do i = 1, size(probes%p)
      if (.not. due(i)) cycle
      call values(probes%p(i), record(k + 1:k + probes%p(i)%nvalue))
      k = k + probes%p(i)%nvalue
    end do
    call par_allgather(record, all)
    if (par_rank() /= 0) return
    k = 0
    do i = 1, size(probes%p)
      if (.not. due(i)) cycle
      associate(p => probes%p(i))
        write(word, '(i0)') state%cycle
        row = trim(word)
        write(word, '(es24.16e3)') state%time
        row = row//','//trim(adjustl(word))
        do j = 1, p%nvalue
          if (p%nodal(j)) then
            write(word, '(es24.16e3)') all(k + j, p%node_rank + 1)
          else
            write(word, '(es24.16e3)') all(k + j, p%zone_rank + 1)
          end if
          row = row//','//trim(adjustl(word))
        end do
        k = k + p%nvalue
        open(newunit=unit, file=p%path, status='old', position='append', action='write')
        write(unit, '(a)') row
        close(unit)
      end associate
    end do

  contains

    !> This rank's values of one probe (those of a node or zone it does not
    !> own are 0 and not used).
    subroutine values(p, v)
      type(probe_t), intent(in) :: p
      real(rk), intent(out) :: v(:)
      integer :: f, j, n, z
      v = 0.0_rk
      n = p%node_local
      z = p%zone_local
      j = 0
      do f = 1, size(p%fields)
        select case (trim(p%fields(f)))
        case ('velocity')
          if (n > 0) v(j + 1:j + 3) = state%node_velocity(:, n)
          j = j + 3
        case ('position')
          if (n > 0) v(j + 1:j + 3) = state%node_position(:, n)
          j = j + 3
        case ('pressure')
          if (z > 0) v(j + 1) = state%zone_pressure(z)
          j = j + 1
        case ('density')
          if (z > 0) v(j + 1) = state%zone_density(z)
          j = j + 1
        case ('energy')
          if (z > 0) v(j + 1) = state%zone_energy(z)
          j = j + 1
        case ('stress')
          if (z > 0) v(j + 1:j + 6) = state%zone_stress(:, z)
          j = j + 6
        case ('plastic_strain')
          if (z > 0) v(j + 1) = state%zone_plastic_strain(z)
          j = j + 1
        case ('viscosity')
          if (z > 0) v(j + 1) = state%zone_viscosity(z)
          j = j + 1
        case ('sound_speed')
          if (z > 0) v(j + 1) = state%zone_sound_speed(z)
          j = j + 1
        end select
      end do
    end subroutine values

  end subroutine probe_sample

end module io_probe
