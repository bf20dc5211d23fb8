!> Lexical scan of a namelist deck: finds every group instance (&name ... /)
!> and the keys assigned in it (with their positions), so that unknown groups,
!> unknown and repeated keys are reported all at once, and a group can be read
!> with its unknown keys blanked out (a namelist read stops at the first one).
module io_deck_scan
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_text, only: to_lower
  use core_keys, only: KEY_LEN
  implicit none
  private
  public :: deck_scan, to_lower, group_text, value_problem, edit_distance, closest_name

  integer, parameter, public :: LINE_LEN = 512
  public :: KEY_LEN
  integer, parameter, public :: VALUE_LEN = 2048

  !> One group instance: its name, where it is, and its keys.
  type, public :: group_instance_t
    character(len=KEY_LEN) :: name = ''
    integer :: first_line = 0 !< line of '&name'
    integer :: last_line = 0 !< line of the closing '/'
    integer :: last_col = 0 !< column of the closing '/'
    integer :: nkey = 0
    character(len=KEY_LEN), allocatable :: key(:) !< key names (lower case, no index)
    character(len=KEY_LEN), allocatable :: key_full(:) !< with their index, if any
    integer, allocatable :: key_line(:), key_col(:) !< where each assignment starts
    !> Each key's value text: comments dropped, blanks outside quotes removed
    !> (a comma where they separate two items), no trailing comma (what a
    !> restart compares and the type check reads).
    character(len=VALUE_LEN), allocatable :: value(:)
  end type group_instance_t

contains

  pure logical function is_name_char(ch)
    character, intent(in) :: ch
    is_name_char = (ch >= 'a' .and. ch <= 'z') .or. (ch >= 'A' .and. ch <= 'Z') .or. &
        (ch >= '0' .and. ch <= '9') .or. ch == '_' .or. ch == '%'
  end function is_name_char

  !> Split the deck lines into group instances with their keys. Text outside
  !> groups must be blank or comments ('!' or '#').
  subroutine deck_scan(lines, groups, ngroup, status)
    character(len=LINE_LEN), intent(in) :: lines(:)
    type(group_instance_t), allocatable, intent(out) :: groups(:)
    integer, intent(out) :: ngroup
    type(status_t), intent(inout) :: status
    type(group_instance_t), allocatable :: tmp(:)
    integer :: il, ic, n, start, j, k, m
    logical :: in_group
    character :: ch, quote
    character(len=LINE_LEN) :: text
    character(len=16) :: lnum
    character(len=KEY_LEN) :: full

    allocate(groups(8))
    ngroup = 0
    in_group = .false.
    quote = ' '
    do il = 1, size(lines)
      text = lines(il)
      n = len_trim(text)
      ic = 0
      do while (ic < n)
        ic = ic + 1
        ch = text(ic:ic)
        if (quote /= ' ') then
          if (ch == quote) quote = ' '
          cycle
        end if
        if (ch == '!' .or. (ch == '#' .and. .not. in_group)) exit
        if (in_group .and. (ch == '&' .or. ch == '$')) then
          call unclosed(ngroup)
          groups(ngroup)%last_line = il
          groups(ngroup)%last_col = ic - 1
          in_group = .false.
        end if
        if (.not. in_group) then
          if (ch == '&' .or. ch == '$') then
            start = ic + 1
            do while (ic < n)
              if (.not. is_name_char(text(ic + 1:ic + 1))) exit
              ic = ic + 1
            end do
            if (ngroup == size(groups)) then
              allocate(tmp(2 * ngroup))
              tmp(1:ngroup) = groups(1:ngroup)
              call move_alloc(tmp, groups)
            end if
            ngroup = ngroup + 1
            groups(ngroup)%name = to_lower(text(start:ic))
            groups(ngroup)%first_line = il
            allocate(groups(ngroup)%key(16), groups(ngroup)%key_full(16))
            allocate(groups(ngroup)%key_line(16), groups(ngroup)%key_col(16))
            in_group = .true.
          else if (ch /= ' ' .and. ch /= achar(9)) then
            write(lnum, '(i0)') il
            call status%add('deck line '//trim(lnum)//': text outside any group: '''// &
                trim(adjustl(text))//'''')
            exit
          end if
        else
          if (ch == '''' .or. ch == '"') then
            quote = ch
          else if (ch == '/') then
            groups(ngroup)%last_line = il
            groups(ngroup)%last_col = ic
            in_group = .false.
          else if (ch == '=') then
            ! The key is the name just before '=', after an optional (index).
            j = ic - 1
            do while (j >= 1)
              if (text(j:j) /= ' ') exit
              j = j - 1
            end do
            m = j
            if (j >= 1) then
              if (text(j:j) == ')') then
                do while (j >= 1)
                  if (text(j:j) == '(') exit
                  j = j - 1
                end do
                j = j - 1
              end if
            end if
            k = j
            do while (k >= 1)
              if (.not. is_name_char(text(k:k))) exit
              k = k - 1
            end do
            if (j >= k + 1) then
              full = to_lower(text(k + 1:m))
              call add_key(groups(ngroup), to_lower(text(k + 1:j)), full, il, k + 1, status)
            end if
          end if
        end if
      end do
    end do
    if (in_group) then
      call unclosed(ngroup)
      groups(ngroup)%last_line = size(lines)
      groups(ngroup)%last_col = len(lines(1))
    end if
    do j = 1, ngroup
      call find_values(lines, groups(j))
    end do

  contains

    subroutine unclosed(g)
      integer, intent(in) :: g
      write(lnum, '(i0)') groups(g)%first_line
      call status%add('&'//trim(groups(g)%name)//': group opened on line '//trim(lnum)// &
          ' is never closed with ''/''')
    end subroutine unclosed

  end subroutine deck_scan

  subroutine add_key(group, key, full, line, col, status)
    type(group_instance_t), intent(inout) :: group
    character(len=*), intent(in) :: key, full
    integer, intent(in) :: line, col
    type(status_t), intent(inout) :: status
    character(len=KEY_LEN), allocatable :: tmp(:), tmp2(:)
    integer, allocatable :: itmp(:), itmp2(:)
    integer :: k
    character(len=32) :: where
    do k = 1, group%nkey
      if (group%key_full(k) /= full) cycle
      write(where, '(a,i0,a,i0)') ' (deck lines ', group%key_line(k), ' and ', line
      call status%add('&'//trim(group%name)//': '//trim(full)//': given twice in one group'// &
          trim(where)//')')
    end do
    if (group%nkey == size(group%key)) then
      allocate(tmp(2 * group%nkey), tmp2(2 * group%nkey), itmp(2 * group%nkey), &
          itmp2(2 * group%nkey))
      tmp(1:group%nkey) = group%key(1:group%nkey)
      tmp2(1:group%nkey) = group%key_full(1:group%nkey)
      itmp(1:group%nkey) = group%key_line(1:group%nkey)
      itmp2(1:group%nkey) = group%key_col(1:group%nkey)
      call move_alloc(tmp, group%key)
      call move_alloc(tmp2, group%key_full)
      call move_alloc(itmp, group%key_line)
      call move_alloc(itmp2, group%key_col)
    end if
    group%nkey = group%nkey + 1
    group%key(group%nkey) = key
    group%key_full(group%nkey) = full
    group%key_line(group%nkey) = line
    group%key_col(group%nkey) = col
  end subroutine add_key

  !> Value text of every key of a group: from after its '=' to the start of
  !> the next key (or the group's closing '/').
  subroutine find_values(lines, group)
    character(len=LINE_LEN), intent(in) :: lines(:)
    type(group_instance_t), intent(inout) :: group
    integer :: k, line, col, end_line, end_col, n
    character :: ch, quote
    character(len=VALUE_LEN) :: v
    logical :: blank
    allocate(group%value(max(group%nkey, 1)))
    do k = 1, group%nkey
      if (k < group%nkey) then
        end_line = group%key_line(k + 1)
        end_col = group%key_col(k + 1) - 1
      else
        end_line = group%last_line
        end_col = group%last_col - 1
      end if
      line = group%key_line(k)
      col = index(lines(line)(group%key_col(k):), '=') + group%key_col(k)
      v = ''
      n = 0
      quote = ' '
      blank = .false.
      do while (line < end_line .or. (line == end_line .and. col <= end_col))
        if (col > len_trim(lines(line))) then
          line = line + 1
          col = 1
          if (quote /= ' ') call put(' ')
          blank = .true.
          cycle
        end if
        ch = lines(line)(col:col)
        if (quote /= ' ') then
          call put(ch)
          if (ch == quote) quote = ' '
        else if (ch == '!') then
          col = len(lines(line)) + 1
          cycle
        else if (ch == ' ' .or. ch == achar(9)) then
          blank = .true.
        else
          ! Blanks between two items separate them, as a comma does.
          if (blank .and. n > 0 .and. ch /= ',') then
            if (v(n:n) /= ',') call put(',')
          end if
          blank = .false.
          if (ch == '''' .or. ch == '"') quote = ch
          call put(ch)
        end if
        col = col + 1
      end do
      do while (n > 0)
        if (v(n:n) /= ',') exit
        v(n:n) = ' '
        n = n - 1
      end do
      group%value(k) = v
    end do

  contains

    subroutine put(c)
      character, intent(in) :: c
      if (n >= VALUE_LEN) return
      n = n + 1
      v(n:n) = c
    end subroutine put

  end subroutine find_values

  !> What is wrong with a key's value for its type ('r' real, 'i' integer,
  !> 'l' logical, 'c' character string in quotes); '' when nothing. Real
  !> values must be finite. The value is split into namelist items (commas, r*c
  !> repeats and null values allowed).
  function value_problem(value, kind) result(problem)
    character(len=*), intent(in) :: value !< as in group_instance_t%value
    character, intent(in) :: kind
    character(len=:), allocatable :: problem
    integer :: i, start, star
    character :: quote
    character(len=:), allocatable :: item
    problem = ''
    start = 1
    quote = ' '
    do i = 1, len_trim(value) + 1
      if (i <= len_trim(value)) then
        if (quote /= ' ') then
          if (value(i:i) == quote) quote = ' '
          cycle
        end if
        if (value(i:i) == '''' .or. value(i:i) == '"') then
          quote = value(i:i)
          cycle
        end if
        if (value(i:i) /= ',') cycle
      end if
      item = value(start:i - 1)
      start = i + 1
      star = index(item, '*')
      if (star > 1) then
        if (verify(item(1:star - 1), '0123456789') == 0) item = item(star + 1:)
      end if
      if (len(item) == 0) cycle
      problem = item_problem(item, kind)
      if (len(problem) > 0) return
    end do
  end function value_problem

  function item_problem(item, kind) result(problem)
    character(len=*), intent(in) :: item
    character, intent(in) :: kind
    character(len=:), allocatable :: problem
    character(len=len(item)) :: low
    character(len=*), parameter :: NOT_FINITE = &
        ' is not a finite number (Inf and NaN are not accepted)'
    character(len=:), allocatable :: shown
    integer :: ios, first
    integer(i8) :: big
    real(rk) :: x
    problem = ''
    low = to_lower(item)
    shown = '''' // item // ''''
    if (item(1:1) == '''' .or. item(1:1) == '"') shown = item
    first = 1
    if (low(1:1) == '+' .or. low(1:1) == '-') first = 2
    select case (kind)
    case ('c')
      if (len(item) >= 2) then
        if ((item(1:1) == '''' .or. item(1:1) == '"') .and. &
            item(len(item):len(item)) == item(1:1)) return
      end if
      problem = shown // ' is not a character string (put it in quotes)'
    case ('l')
      if (low(1:1) == '.') first = 2
      if (len(low) >= first) then
        if (low(first:first) == 't' .or. low(first:first) == 'f') return
      end if
      problem = shown // ' is not a logical (.true. or .false.)'
    case ('i')
      if (len(low) >= first) then
        if (verify(low(first:), '0123456789') == 0) then
          big = huge(1_i8)
          if (len(low) - first + 1 <= 18) read(low, *, iostat=ios) big
          if (abs(big) <= huge(1)) return
          problem = shown // ' is out of the integer range'
          return
        end if
      end if
      problem = shown // ' is not an integer'
    case ('r')
      if (len(low) >= first) then
        select case (low(first:))
        case ('inf', 'infinity', 'nan')
          problem = shown // NOT_FINITE
          return
        end select
      end if
      if (.not. real_syntax(low)) then
        problem = shown // ' is not a real number'
        return
      end if
      if (overflows(low)) then
        problem = shown // NOT_FINITE
        return
      end if
      read(low, *, iostat=ios) x
      if (ios /= 0) then
        problem = shown // NOT_FINITE
      else if (.not. ieee_is_finite(x)) then
        problem = shown // NOT_FINITE
      end if
    end select
  end function item_problem

  !> Whether a real literal (real_syntax true, lower case) is beyond the
  !> largest real(rk), found from its digits without converting it (a
  !> conversion that overflows would trap in a build with FPE traps).
  logical function overflows(text)
    character(len=*), intent(in) :: text
    character(len=*), parameter :: LARGEST = '17976931348623157' !< huge(1.0_rk)
    integer, parameter :: LARGEST_EXPONENT = 308
    character(len=len(text)) :: digits
    integer :: i, n, nint, ndig, ios
    integer(i8) :: ex, magnitude
    logical :: point
    character(len=len(LARGEST)) :: lead
    overflows = .false.
    n = len(text)
    i = 1
    if (text(1:1) == '+' .or. text(1:1) == '-') i = 2
    ndig = 0
    nint = 0
    point = .false.
    digits = ''
    do while (i <= n)
      if (text(i:i) == '.') then
        point = .true.
      else if (text(i:i) >= '0' .and. text(i:i) <= '9') then
        if (ndig == 0 .and. text(i:i) == '0') then
          if (point) nint = nint - 1
        else
          ndig = ndig + 1
          digits(ndig:ndig) = text(i:i)
          if (.not. point) nint = nint + 1
        end if
      else
        exit
      end if
      i = i + 1
    end do
    if (ndig == 0) return
    ex = 0
    if (i <= n) then
      if (index('edq', text(i:i)) > 0) i = i + 1
      if (len_trim(text(i:)) > 12) then
        overflows = text(i:i) /= '-'
        return
      end if
      read(text(i:), *, iostat=ios) ex
      if (ios /= 0) return
    end if
    magnitude = nint - 1 + ex
    if (magnitude > LARGEST_EXPONENT) then
      overflows = .true.
    else if (magnitude == LARGEST_EXPONENT) then
      lead = digits(1:min(ndig, len(lead)))
      do i = ndig + 1, len(lead)
        lead(i:i) = '0'
      end do
      overflows = lead > LARGEST
    end if
  end function overflows

  !> A Fortran real literal: sign, digits with an optional point (at least one
  !> digit), an optional exponent (e, d or q, or a bare sign) with digits.
  pure logical function real_syntax(text)
    character(len=*), intent(in) :: text
    integer :: i, n, digits
    logical :: point
    real_syntax = .false.
    n = len(text)
    i = 1
    if (n == 0) return
    if (text(1:1) == '+' .or. text(1:1) == '-') i = 2
    digits = 0
    point = .false.
    do while (i <= n)
      if (text(i:i) >= '0' .and. text(i:i) <= '9') then
        digits = digits + 1
      else if (text(i:i) == '.' .and. .not. point) then
        point = .true.
      else
        exit
      end if
      i = i + 1
    end do
    if (digits == 0) return
    if (i > n) then
      real_syntax = .true.
      return
    end if
    if (index('edq', text(i:i)) > 0) then
      i = i + 1
      if (i > n) return
    else if (text(i:i) /= '+' .and. text(i:i) /= '-') then
      return
    end if
    if (text(i:i) == '+' .or. text(i:i) == '-') i = i + 1
    if (i > n) return
    real_syntax = verify(text(i:), '0123456789') == 0
  end function real_syntax

  !> Levenshtein distance between two names (trailing blanks ignored).
  pure integer function edit_distance(a, b)
    character(len=*), intent(in) :: a, b
    integer :: la, lb, i, j
    integer, allocatable :: prev(:), cur(:)
    la = len_trim(a)
    lb = len_trim(b)
    allocate(prev(0:lb), cur(0:lb))
    prev = [(j, j = 0, lb)]
    do i = 1, la
      cur(0) = i
      do j = 1, lb
        cur(j) = min(prev(j) + 1, cur(j - 1) + 1, prev(j - 1) + merge(0, 1, a(i:i) == b(j:j)))
      end do
      prev = cur
    end do
    edit_distance = prev(lb)
  end function edit_distance

  !> The candidate closest to name when at most 2 edits away (and fewer edits
  !> than the name has characters), else ''.
  function closest_name(name, candidates) result(best)
    character(len=*), intent(in) :: name
    character(len=*), intent(in) :: candidates(:)
    character(len=:), allocatable :: best
    integer :: i, d, dbest
    best = ''
    dbest = 3
    do i = 1, size(candidates)
      d = edit_distance(name, candidates(i))
      if (d < dbest .and. d < len_trim(name)) then
        dbest = d
        best = trim(candidates(i))
      end if
    end do
  end function closest_name

  !> The group's lines, ready for a namelist read: assignments to keys not in
  !> known are blanked out, and the group is closed at its end.
  function group_text(lines, group, known, skip) result(text)
    character(len=LINE_LEN), intent(in) :: lines(:)
    type(group_instance_t), intent(in) :: group
    character(len=KEY_LEN), intent(in) :: known(:)
    logical, intent(in), optional :: skip(:) !< blank these keys too (bad values)
    character(len=LINE_LEN), allocatable :: text(:)
    integer :: k, line, col, end_line, end_col, first
    first = group%first_line
    allocate(text(group%last_line - first + 1))
    text = lines(first:group%last_line)
    ! Whatever follows the end of the group on its last line is not part of it.
    if (group%last_col < LINE_LEN) text(size(text))(group%last_col + 1:) = ''
    if (text(size(text))(max(1, group%last_col):max(1, group%last_col)) /= '/') &
        text(size(text)) = trim(text(size(text)))//' /'
    do k = 1, group%nkey
      if (any(known == group%key(k))) then
        if (.not. present(skip)) cycle
        if (.not. skip(k)) cycle
      end if
      if (k < group%nkey) then
        end_line = group%key_line(k + 1)
        end_col = group%key_col(k + 1) - 1
      else
        end_line = group%last_line
        end_col = group%last_col - 1
      end if
      line = group%key_line(k)
      col = group%key_col(k)
      do while (line < end_line .or. (line == end_line .and. col <= end_col))
        if (col > LINE_LEN) then
          line = line + 1
          col = 1
          cycle
        end if
        text(line - first + 1)(col:col) = ' '
        col = col + 1
      end do
    end do
  end function group_text

end module io_deck_scan
